#pragma once
// `tmdem study accuracy` (contract section 5): a work-precision study of the thermal integrators
// on a scene's frozen thermal problem.
//
// Runs, all from the scene's initial temperatures to simulation.duration:
//   explicit   forward Euler at h = 0.9 x the stability bound (2 / lambda_max, Gershgorin), then
//              h / 4, h / 16, ... (explicit_rungs = 12 rungs); a rung whose projected work
//              ceil(duration / h) x (nodes + edges + wall edges) exceeds explicit_work_budget
//              is skipped (2e9 is a few seconds of wall time).
//   cvode, ida with klu and pcg, at relative tolerances 1e-2, 1e-4, 1e-6, 1e-8, 1e-10 and the
//              absolute tolerance equal to the relative one, read in kelvin (atol = rtol K).
//              First the methods with iterative solvers, then klu (predicted from their counts,
//              and the slowest on large 3D beds); each loose to tight, every method at one
//              tolerance before any at the next.
// Before each run its wall time is predicted (AccuracyRunForecast.h); a run is skipped, and
// kept in `runs` with skipped = true, its prediction and why, when
//   - its prediction exceeds implicit_time_budget_s (implicit runs), or
//   - the study's time so far (reference included) plus its prediction exceeds
//     study_time_budget_s, or
//   - a looser run of its method was skipped or took longer than implicit_time_budget_s
//     (a tighter tolerance costs more).
// A run without a prediction (an iterative method's first run; a dynamic scene's explicit
// rungs) is made. Why: a study that starts every run does not end on a large 3D bed (KLU's
// fill-in: 35-100 s for one run at 24,389 particles, out of memory at 10^6), and a skipped
// run's predicted cost still says what the method would take.
// Reference: for a linear network (no radiation) of any size, the exact solution with its own
// error bound in kelvin (coupling/studies/SparseExactReference.h: Chebyshev series of the
// matrix exponential on the sparse system); otherwise (and for a dynamic scene's replay)
// CVODE/KLU at rtol = atol = 1e-12, whose error is not known.
// Each run: wall time of the integrator's initialize + advance_to only (steady_clock; runs
// under repeat_below_s are repeated up to max_timings times and the least time kept; the
// thread CPU time of that timing is kept too), the
// largest |T_i - T_ref,i| over all particles at the end time, steps and right-hand-side
// evaluations. A run that fails (solver error, non-finite temperature) is kept with ok = false
// and its message: it is printed, never written to the CSV.
#include <cstddef>
#include <functional>
#include <limits>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coupling/bridge/CouplingStrategy.h"
#include "coupling/scene/Scene.h"
#include "thermal/modes/HeatTransferMode.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

// "cvode/amg"-style names (INTEGRATOR/LINEAR_SOLVER, implicit integrators only) parsed into
// AccuracyStudyOptions::implicit_methods; on a bad name `problem` says which and lists the valid
// ones, and the result is empty.
// An implicit method of the study: its integrator and linear solver, parsed once from the names.
struct ImplicitMethod {
  thermal::IntegratorKind integrator = thermal::IntegratorKind::Cvode;
  thermal::LinearSolverKind solver = thermal::LinearSolverKind::Klu;
  std::string integrator_name() const { return std::string(thermal::name_of(integrator)); }
  std::string solver_name() const { return std::string(thermal::name_of(solver)); }
};

std::vector<ImplicitMethod> parse_implicit_methods(const std::vector<std::string>& names,
                                                   std::string& problem);

struct AccuracyStudyOptions {
  std::vector<double> relative_tolerances{1e-2, 1e-4, 1e-6, 1e-8, 1e-10};
  std::vector<ImplicitMethod> implicit_methods{
      {thermal::IntegratorKind::Cvode, thermal::LinearSolverKind::Klu},
      {thermal::IntegratorKind::Cvode, thermal::LinearSolverKind::Pcg},
      {thermal::IntegratorKind::Ida, thermal::LinearSolverKind::Klu},
      {thermal::IntegratorKind::Ida, thermal::LinearSolverKind::Pcg}};
  int explicit_rungs = 12;
  double explicit_first_fraction = 0.9;      // of the stability bound
  double explicit_rung_factor = 4.0;         // each rung's step is the previous one / this
  double explicit_work_budget = 2.0e9;       // steps x (nodes + edges + wall edges)
  // s of one implicit run: one predicted to take longer is skipped, and once one took longer its
  // method's tighter tolerances are. Why: on a 100,352-particle stiff bed cvode/klu at rtol 1e-2
  // alone took 215 s (KLU fill-in), so its tighter runs and ida/klu's would take hours while
  // pcg's take seconds.
  double implicit_time_budget_s = 60.0;
  // s of the whole study from its start (reference included): a run predicted to end past it is
  // skipped. 180 s of runs, so that a study of a 25,000-particle 3D bed, set-up included, ends
  // within 4 minutes (docs/benchmarks.md).
  double study_time_budget_s = 180.0;
  // Explicit steps timed to predict the first explicit rung when no explicit run was made yet.
  int explicit_probe_steps = 100;
  double repeat_below_s = 0.05;
  int max_timings = 10;
  double reference_tolerance = 1e-12;        // CVODE/KLU reference: rtol = atol (K)
  // Explicit ladder start: 0 takes the bound of the system's current network; a dynamic
  // scene passes the smallest bound over its recorded steps.
  double stability_bound_s = 0.0;
  // Largest explicit step (a dynamic scene: the mechanical step); 0 = none.
  double max_explicit_step_s = 0.0;
  // Asked before each run: true ends the study early (an interrupted study). The runs not made
  // are listed as skipped, "the study was interrupted"; empty: never.
  std::function<bool()> stop;
};

// How one run gets from t = 0 to the end time. Empty: initialize, then one advance on the
// frozen network. A dynamic scene replays its recorded contact graph (ThermalReplay) with the
// given coupling strategy (Continue for the runs, Restart for the reference).
using ThermalDriver = std::function<void(thermal::ThermalIntegrator&, std::span<const double> T0_K,
                                         double end_time_s, CouplingStrategy coupling)>;

// The CSV's linear_solver column for the explicit update.
inline constexpr const char* kNoLinearSolver = "none";
// Why a run was not made when the study was stopped (AccuracyStudyOptions::stop).
inline constexpr const char* kInterruptedRunReason = "not made: the study was interrupted";

struct AccuracyRun {
  std::string method;          // explicit | cvode | ida
  std::string linear_solver;   // klu | pcg; "none" for explicit
  double parameter = 0.0;      // explicit: step, s; otherwise the relative tolerance
  double max_error_K = 0.0;
  double wall_time_s = 0.0;    // least over the timings
  double cpu_time_s = 0.0;     // thread CPU time of the same run (not in the CSV): close to the
                               // wall time unless the machine is busy with other work
  long steps = 0;
  long rhs_evals = 0;
  long linear_setups = 0;      // (not in the CSV) what the forecasts of klu runs scale with
  int timings = 0;             // how many times it was run and timed
  bool ok = true;              // made and successful
  std::string message;         // why it failed, or why it was skipped
  bool skipped = false;        // not made (ok = false): predicted too slow, see `message`
  // The wall time predicted before the run (AccuracyRunForecast.h); NaN: no prediction.
  double predicted_wall_time_s = std::numeric_limits<double>::quiet_NaN();
  std::string prediction_basis;  // how it was predicted

  bool failed() const { return !ok && !skipped; }

  // "explicit", "cvode/klu", ...
  bool is_explicit() const { return method == thermal::name_of(thermal::IntegratorKind::Explicit); }
  std::string label() const { return is_explicit() ? method : method + "/" + linear_solver; }
};

struct AccuracyReference {
  bool exact = false;
  std::string description;     // what was used and why; the error bound when known
  std::vector<double> T_K;     // at the end time
  double wall_time_s = 0.0;
  // >= max_i |T_K[i] - exact T_i| (exact reference); NaN when not known (CVODE/KLU reference).
  double error_bound_K = std::numeric_limits<double>::quiet_NaN();
};

struct AccuracyStudyResult {
  double end_time_s = 0.0;
  std::size_t nodes = 0, edges = 0, wall_edges = 0;
  double stability_bound_s = 0.0;
  AccuracyReference reference;
  // Explicit rungs first (largest step first), then each implicit method in the options'
  // order, loose to tight; skipped runs included (skipped = true).
  std::vector<AccuracyRun> runs;
  double wall_time_s = 0.0;             // the whole study, reference included
};

// The reference could not be computed (exit code 3).
struct ReferenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The study on `system` from T0_K over [0, end_time_s]. `base` gives what is common to every
// run (max_temperature_K for the explicit bound); tolerances, step and linear solver are set
// per run (the exact reference reads the modes' own parameters). Progress lines go to `log`
// (nothing if null). Throws ReferenceError when the reference fails.
AccuracyStudyResult run_accuracy_study(thermal::ThermalSystem& system,
                                       std::span<const double> T0_K, double end_time_s,
                                       const thermal::IntegratorSettings& base,
                                       const AccuracyStudyOptions& options, std::ostream* log,
                                       const ThermalDriver& driver = {});

// One timed run of `method` with `settings` against `reference_T_K` (the study's building block,
// also used by the benchmark). Never throws for solver failures: they give ok = false.
AccuracyRun timed_accuracy_run(thermal::ThermalSystem& system, const std::string& method,
                               const thermal::IntegratorSettings& settings,
                               std::span<const double> T0_K, double end_time_s,
                               std::span<const double> reference_T_K,
                               const AccuracyStudyOptions& options,
                               const ThermalDriver& driver = {});

// The study's reference alone (as in run_accuracy_study). Throws ReferenceError.
AccuracyReference accuracy_reference(thermal::ThermalSystem& system, std::span<const double> T0_K,
                                     double end_time_s, const thermal::IntegratorSettings& base,
                                     const AccuracyStudyOptions& options,
                                     const ThermalDriver& driver = {});

}  // namespace tmdem::coupling
