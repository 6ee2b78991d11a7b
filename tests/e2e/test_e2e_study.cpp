// End to end: `tmdem study accuracy` (contract section 5) on a small mechanics-off lattice.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// 3 x 3 x 2 lattice of touching spheres on a heated floor, constant conductance, one hot
// particle and one held cold one: linear and small, so the reference is the exact exponential.
const std::string kStudyLattice =
    thermal_scene()
        .set("simulation.duration", 1000.0)
        .add("generate", lattice({3, 3, 2}))
        .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
        .add("assign", assign_ids({17}, {{"temperature", 283.15}, {"fixed_temperature", true}}))
        .add("wall", floor_wall({{"temperature", 353.15}}));

struct Row {
  std::string method, solver;
  double parameter, error, wall;
  long steps, rhs;
  std::string status;   // ok | skipped
  double predicted;     // NaN when the study made no prediction
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

double number_or_nan(const std::string& cell) { return cell.empty() ? std::nan("") : std::stod(cell); }

// The study's CSV: the contract's header and its extension, then one row of 9 cells per run
// made (status ok, every cell a number but perhaps the prediction); then the skipped runs' CSV
// beside it (OUT.skipped.csv: method, solver, parameter, prediction, the quoted reason), as rows
// with status skipped and no measurement.
std::vector<Row> read_study_csv(const std::string& path) {
  std::vector<Row> rows;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) {
    ADD_FAILURE() << "no header in " << path;
    return rows;
  }
  EXPECT_EQ(line, "method,linear_solver,parameter,max_error_K,wall_time_s,steps,rhs_evals,"
                  "status,predicted_wall_time_s");
  while (std::getline(in, line)) {
    const auto c = split(line);
    if (c.size() != 9u) {
      ADD_FAILURE() << "not 9 cells: " << line;
      continue;
    }
    EXPECT_EQ(c[7], "ok") << line;
    rows.push_back({c[0], c[1], std::stod(c[2]), std::stod(c[3]), std::stod(c[4]), std::stol(c[5]),
                    std::stol(c[6]), c[7], number_or_nan(c[8])});
  }
  const std::string skipped_path = path.substr(0, path.size() - 4) + ".skipped.csv";
  std::ifstream skipped(skipped_path);
  if (!std::getline(skipped, line)) {
    ADD_FAILURE() << "no header in " << skipped_path;
    return rows;
  }
  EXPECT_EQ(line, "method,linear_solver,parameter,predicted_wall_time_s,reason");
  while (std::getline(skipped, line)) {
    // Four cells, then the reason in quotes (it may hold commas).
    const auto quote = line.find(",\"");
    const auto c = split(line.substr(0, quote + 1));
    if (quote == std::string::npos || c.size() != 5u || line.back() != '"') {
      ADD_FAILURE() << "not 4 cells and a quoted reason: " << line;
      continue;
    }
    rows.push_back({c[0], c[1], std::stod(c[2]), std::nan(""), std::nan(""), 0L, 0L, "skipped",
                    number_or_nan(c[3])});
  }
  return rows;
}

// The rows of runs made.
std::vector<Row> made_rows(const std::vector<Row>& rows) {
  std::vector<Row> made;
  for (const auto& row : rows)
    if (row.status == "ok") made.push_back(row);
  return made;
}

}  // namespace

TEST(EndToEndStudy, AccuracyStudyCsvAndConvergence) {
  const auto dir = scratch_dir("study");
  write_file(dir + "/lattice.toml", kStudyLattice);
  // 7 explicit rungs keep the test short (the smallest step is 0.9 bound / 4^6).
  const auto r = run_tmdem("study accuracy lattice.toml --csv out.csv --explicit-rungs 7 "
                           "--set simulation.duration=20.0",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("exact matrix exponential"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("end time (simulation.duration) 20 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max error <= 1e-03 K"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max error <= 1e-06 K"), std::string::npos) << r.output;

  const std::vector<Row> rows = read_study_csv(dir + "/out.csv");
  EXPECT_EQ(made_rows(rows).size(), rows.size()) << "a run of this small study was skipped";
  for (const auto& row : rows) {
    EXPECT_TRUE(std::isfinite(row.error)) << row.method << " " << row.parameter;
    EXPECT_GE(row.wall, 0.0) << row.method << " " << row.parameter;
  }
  std::map<std::string, int> count;
  for (const auto& row : rows) ++count[row.method + "/" + row.solver];
  EXPECT_EQ(count["explicit/none"], 7);
  EXPECT_EQ(count["cvode/klu"], 5);
  EXPECT_EQ(count["cvode/pcg"], 5);
  EXPECT_EQ(count["ida/klu"], 5);
  EXPECT_EQ(count["ida/pcg"], 5);

  // Explicit: each rung a quarter of the step before, and first order in the asymptotic range
  // (the last three ratios): error / 4 within 20%.
  std::vector<Row> ex;
  for (const auto& row : rows)
    if (row.method == "explicit") ex.push_back(row);
  ASSERT_EQ(ex.size(), 7u);
  for (std::size_t k = 1; k < ex.size(); ++k) {
    EXPECT_NEAR(ex[k - 1].parameter / ex[k].parameter, 4.0, 1e-9);
    EXPECT_GT(ex[k].steps, ex[k - 1].steps);
  }
  for (std::size_t k = ex.size() - 3; k < ex.size(); ++k) {
    const double ratio = ex[k - 1].error / ex[k].error;
    EXPECT_GT(ratio, 3.2) << "rung " << k;
    EXPECT_LT(ratio, 4.8) << "rung " << k;
  }

  // CVODE at rtol = atol = 1e-10 is within 1e-6 K of the exact answer; errors fall with rtol.
  int tight = 0;
  for (const auto& row : rows) {
    if (row.method == "cvode" && row.parameter == 1e-10) {
      EXPECT_LT(row.error, 1e-6) << row.solver;
      ++tight;
    }
    if (row.method == "cvode" && row.solver == "klu" && row.parameter == 1e-2) {
      EXPECT_GT(row.error, 1e-4);
    }
  }
  EXPECT_EQ(tight, 2);
}

// --implicit-budget: an implicit run predicted to take longer is skipped, with its prediction,
// and so are a method's tighter runs once one of its runs took longer. With a budget of 0 s the
// iterative methods' loosest runs, which have no prediction, are made and take longer; every
// other implicit run is skipped and said so, in the output and as a row of the skipped runs' CSV
// with its predicted cost (klu's from its sibling's counts and KLU's analysis).
TEST(EndToEndStudy, ImplicitTimeBudgetSkipsRunsPredictedOverIt) {
  const auto dir = scratch_dir("study_budget");
  write_file(dir + "/lattice.toml", kStudyLattice);
  const auto r = run_tmdem("study accuracy lattice.toml --csv out.csv --explicit-rungs 1 "
                           "--implicit-budget 0 --set simulation.duration=20.0",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> made, skipped;
  for (const auto& row : read_study_csv(dir + "/out.csv")) {
    if (row.method == "explicit") continue;
    const std::string name = row.method + "/" + row.solver;
    if (row.status == "ok") {
      made.push_back(name);
      EXPECT_EQ(row.parameter, 1e-2) << name;  // the loosest only
    } else {
      skipped.push_back(name);
      EXPECT_GT(row.predicted, 0.0) << name << " " << row.parameter;
    }
  }
  EXPECT_EQ(made, (std::vector<std::string>{"cvode/pcg", "ida/pcg"}));
  EXPECT_EQ(skipped.size(), 18u);  // 4 methods x 5 tolerances, less the two made
  for (const char* said : {"ida/pcg rtol = 0.0001: skipped: rtol 1e-02 took",
                           "cvode/klu rtol = 0.01: skipped: predicted",
                           "over the 0 s budget of one run (--implicit-budget)",
                           "cvode/klu: not reached; skipped from rtol = 1e-02 on (predicted"})
    EXPECT_NE(r.output.find(said), std::string::npos) << said << "\n" << r.output;
}

// --time-budget: a run predicted to end the study past it is skipped. At 0 s every run with a
// prediction is: the explicit rung (predicted from a probe of explicit steps) and every implicit
// run but the iterative methods' loosest.
TEST(EndToEndStudy, StudyTimeBudgetSkipsRunsPredictedToEndPastIt) {
  const auto dir = scratch_dir("study_time_budget");
  write_file(dir + "/lattice.toml", kStudyLattice);
  const auto r = run_tmdem("study accuracy lattice.toml --csv out.csv --explicit-rungs 2 "
                           "--time-budget 0 --set simulation.duration=20.0",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = read_study_csv(dir + "/out.csv");
  ASSERT_EQ(rows.size(), 22u);  // 2 explicit rungs + 4 methods x 5 tolerances, made or skipped
  std::vector<std::string> made;
  for (const auto& row : made_rows(rows)) made.push_back(row.method + "/" + row.solver);
  EXPECT_EQ(made, (std::vector<std::string>{"cvode/pcg", "ida/pcg"}));
  for (const auto& row : rows)
    if (row.method == "explicit") {
      EXPECT_EQ(row.status, "skipped");
      EXPECT_GT(row.predicted, 0.0);
    }
  EXPECT_NE(r.output.find("past its 0 s budget"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(--time-budget)"), std::string::npos) << r.output;
}

// --methods chooses the implicit methods: cvode/amg alone gives five amg rows, each converging
// like cvode/pcg (within 1e-6 K of the exact answer at 1e-10); a bad name is refused (exit 2)
// with the valid ones listed, before any computation.
TEST(EndToEndStudy, MethodsChooseTheImplicitMethods) {
  const auto dir = scratch_dir("study_methods");
  write_file(dir + "/lattice.toml", kStudyLattice);
  auto r = run_tmdem("study accuracy lattice.toml --csv out.csv --explicit-rungs 0 "
                     "--methods cvode/amg --set simulation.duration=20.0",
                     dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = made_rows(read_study_csv(dir + "/out.csv"));
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.method + "/" + row.solver, "cvode/amg");
    if (row.parameter == 1e-10) {
      EXPECT_LT(row.error, 1e-6);
    }
  }
  r = run_tmdem("study accuracy lattice.toml --csv bad.csv --methods cvode/amg,ida/lu", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("\"ida/lu\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ida/amg"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad.csv"));
  r = run_tmdem("study accuracy lattice.toml --methods explicit/klu", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--explicit-rungs"), std::string::npos) << r.output;
}

// A signal ends the study after the current run: the runs made are reported and written, the
// runs left are listed in OUT.skipped.csv as not made ("the study was interrupted"), one line
// counts both, exit 143. The signal is sent once the first run is reported: the 31 runs left
// take seconds (the smallest explicit steps alone, 10^6 to 10^7 steps), the signal's way
// milliseconds.
TEST(EndToEndStudy, SigtermEndsTheStudyAfterTheCurrentRunWithTheRunsMade) {
  const auto dir = scratch_dir("study_interrupt");
  write_file(dir + "/lattice.toml", kStudyLattice);
  const pid_t child = spawn_tmdem({"study", "accuracy", "lattice.toml", "--csv", "out.csv", "--explicit-rungs",
                                   "12", "--set", "simulation.duration=20.0"},
                                  dir);
  ASSERT_GT(child, 0);
  const int status = signal_once_logged(child, dir, ": max error", SIGTERM);
  const std::string log = text_of(dir + "/child.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  ASSERT_EQ(WEXITSTATUS(status), 143) << log;
  const auto rows = read_study_csv(dir + "/out.csv");
  const auto made = made_rows(rows);
  EXPECT_GE(made.size(), 1u);
  EXPECT_EQ(rows.size(), 32u);  // 12 rungs + 4 methods x 5 tolerances, made or not
  std::size_t not_made = 0;
  for (const auto& row : rows)
    if (row.status == "skipped") ++not_made;
  EXPECT_GE(not_made, 20u);  // at least the implicit runs
  EXPECT_EQ(text_of(dir + "/out.skipped.csv").find("the study was interrupted") != std::string::npos, true);
  EXPECT_NE(log.find("interrupted by SIGTERM: " + std::to_string(made.size()) + " runs made, "), std::string::npos)
      << log;
  for (const auto& row : made) EXPECT_TRUE(std::isfinite(row.error)) << row.method;
}

TEST(EndToEndStudy, ExitCodes) {
  const auto dir = scratch_dir("study_exit");
  write_file(dir + "/lattice.toml", kStudyLattice);
  // Missing scene: 2, naming it.
  auto r = run_tmdem("study accuracy missing.toml --csv out.csv", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.toml"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.csv"));
  // Bad arguments: 2.
  r = run_tmdem("study accuracy lattice.toml --no-such-option", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_tmdem("study accuracy", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // Invalid --set: 2.
  r = run_tmdem("study accuracy lattice.toml --set thermal.integratr=ida", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // CSV not writable: 4, naming the file.
  r = run_tmdem("study accuracy lattice.toml --csv no/such/folder/out.csv", dir);
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("no/such/folder/out.csv"), std::string::npos) << r.output;
}

TEST(EndToEndStudy, DynamicSceneReplaysItsRecordedContactGraph) {
  // Three spheres dropped onto a floor held at 400 K: contacts close during the run.
  const auto dir = scratch_dir("study_dynamic");
  write_file(dir + "/drop.toml",
             copper_drop_scene(0.3)
                 .add("particle", particle({0.002, 0.003, 0.0}, {{"material", "copper"}}))
                 .add("particle", particle({0.002, 0.0052, 0.0}, {{"material", "copper"}}))
                 .add("particle", particle({0.0045, 0.004, 0.0}, {{"material", "copper"}}))
                 .add("wall", floor_wall({{"material", "copper"}, {"temperature", 400.0}}))
                 .set("output.file", "drop.h5"));
  const auto r = run_tmdem("study accuracy drop.toml --csv out.csv --explicit-rungs 3", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("restarted every mechanical step"), std::string::npos) << r.output;
  int explicit_rows = 0, cvode_rows = 0;
  double cvode_tight_error = 1e9;
  for (const auto& row : made_rows(read_study_csv(dir + "/out.csv"))) {
    if (row.method == "explicit") {
      ++explicit_rows;
      EXPECT_LE(row.parameter, 1e-3 * (1 + 1e-12)) << "explicit step above the mechanical step";
    }
    if (row.method == "cvode" && row.solver == "klu") {
      ++cvode_rows;
      if (row.parameter == 1e-10) cvode_tight_error = row.error;
    }
  }
  EXPECT_EQ(explicit_rows, 3);
  EXPECT_EQ(cvode_rows, 5);
  // Heat does flow (the floor is 100 K hotter) and the tight run follows the reference.
  EXPECT_LT(cvode_tight_error, 1e-3);
}
