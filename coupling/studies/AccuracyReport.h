#pragma once
// Output of the accuracy study (contract section 5): the CSV, the human-readable table, and
// where each method reaches 1e-3 K and 1e-6 K.
//
// CSV: the contract's header `method,linear_solver,parameter,max_error_K,wall_time_s,steps,
// rhs_evals` extended by two columns, `status,predicted_wall_time_s`, then one row per run:
// status "ok" for a run made (predicted_wall_time_s: its prediction, empty if none), "skipped"
// for a run the study did not make because it was predicted too slow (its four measured cells
// empty, predicted_wall_time_s its predicted cost, empty if none). linear_solver is "none" for
// the explicit update; parameter is the step (s) for explicit, the relative tolerance otherwise;
// numbers are written in the shortest form that reads back to the same double. Failed runs are
// not in the CSV (the table and stderr show them with their message). Why the extension: a
// skipped run is said so where the runs are read, with what it would cost, and the contract's
// seven columns keep their names and places.
#include <ostream>
#include <string>
#include <vector>

#include "coupling/common/ShortestNumber.h"
#include "coupling/studies/AccuracyStudy.h"

namespace tmdem::coupling {

inline constexpr const char* kAccuracyCsvHeader =
    "method,linear_solver,parameter,max_error_K,wall_time_s,steps,rhs_evals";
// The extension's columns, after the contract's.
inline constexpr const char* kAccuracyCsvExtension = "status,predicted_wall_time_s";
// The runs skipped as predicted too slow, in a CSV of their own beside the study's.
inline constexpr const char* kSkippedRunsCsvHeader =
    "method,linear_solver,parameter,predicted_wall_time_s,reason";

// One row per run made (status "ok"; every cell of the contract's seven a number), in the
// study's order: the contract's table, which a script can read as numbers row by row. Failed
// and skipped runs are not runs made: they have no row here.
void write_accuracy_csv(std::ostream& out, const std::vector<AccuracyRun>& runs);
// One row per run skipped as predicted too slow: its prediction (s; empty where the study made
// none) and the study's reason, quoted. Just the header when none was skipped.
void write_skipped_runs_csv(std::ostream& out, const std::vector<AccuracyRun>& runs);
// Where the skipped runs of a study writing `csv_path` go: OUT.csv -> OUT.skipped.csv
// (any other name: NAME.skipped.csv).
std::string skipped_runs_csv_path(const std::string& csv_path);

// The successful run of `label` ("explicit", "cvode/klu", ...) with the least wall time among
// those whose max error is at most target_K; null if none.
const AccuracyRun* cheapest_reaching(const std::vector<AccuracyRun>& runs, const std::string& label,
                                     double target_K);

// What the explicit update would cost to reach target_K, from its smallest-step successful run
// (h0, e0, wall time w0 over n0 steps), assuming first order (error = c h, c = e0 / h0) and the
// same cost per step: h = target / c, wall time = (w0 / n0) ceil(end_time / h).
struct ExplicitProjection {
  bool available = false;
  double error_constant_K_per_s = 0.0;   // c
  double step_s = 0.0;                   // h reaching the target
  double steps = 0.0;
  double cost_per_step_s = 0.0;
  double wall_time_s = 0.0;
  double basis_step_s = 0.0;             // h0
  double observed_order = 0.0;           // from the two smallest steps; 0 if fewer than two
};
ExplicitProjection project_explicit(const std::vector<AccuracyRun>& runs, double end_time_s,
                                    double target_K);

// Setup lines, the table of every run (failed ones with their message) and the target summary.
void print_accuracy_report(std::ostream& out, const AccuracyStudyResult& result,
                           const AccuracyStudyOptions& options);


}  // namespace tmdem::coupling
