#pragma once
// How long a run of the accuracy study will take, predicted before it is made, so that the study
// skips a run predicted to be slow (and still shows what it would cost) instead of starting it
// (coupling/studies/AccuracyStudy.h). Why: on a 24,389-particle 3D lattice one cvode/klu run at
// rtol 1e-2 took 35-100 s (KLU's fill-in) where cvode/pcg took 0.3 s, and at 10^6 particles
// KLU's first factorisation runs out of memory; a study that starts such runs does not end.
//
// Implicit runs (integrator I, linear solver L, relative tolerance r), from the runs the study
// has made so far; a sibling is a run of I with another linear solver (the cheapest at r):
//   after a run of I/L: its last (tightest) run's wall time x how much the sibling's cost grew
//     from that run's tolerance to r (klu: the model below, others: right-hand sides), else x
//     the growth of its own steps per factor 100 in tolerance between its last two runs
//     (kDefaultGrowthPer100 with one run); at least x 1, a tighter tolerance costs more.
//   klu's first run: model = setups x one factorisation + right-hand sides x one solve, as
//     timed by the study (thermal/integrators/KluFactorisationCost.h), with the sibling's counts
//     at r (else its tightest run's, grown as above), plus the sibling's wall time (right-hand
//     sides, Jacobians, error tests). The counts hardly depend on the linear solver: on the
//     stiff bed cvode/klu and cvode/pcg take the same 17-314 steps and 9-42 setups, ida/klu
//     up to 1.6x the setups of ida/pcg. When the factorisation was not timed (its flops alone
//     put it over the budget): a lower bound, max(1, setups) factorisations at
//     kKluFastestFlopsPerSecond.
//   pcg, amg: no prediction before their first run (made unpredicted: at 10^6 particles their
//     loosest runs take tens of seconds).
// Explicit rungs: work units (steps x (particles + edges + wall edges)) x the seconds per unit
//   of the smallest-step explicit run made so far, else of a probe (a few explicit steps timed
//   by the study).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "coupling/studies/AccuracyStudy.h"
#include "thermal/integrators/KluFactorisationCost.h"

namespace tmdem::coupling {

// The fastest KLU factorisation measured (AMD, Laplacians of 3D lattices and slabs of 8,000-25,088
// nodes, 0.6-8.6 GFlop; 2026-11-28, the 2-core development machine): 4.9 GFlop/s, where the same
// factorisations ran at 0.44-1.7 GFlop/s when other jobs shared the machine. A factorisation's
// flops over it bound its time from below, before any is made.
inline constexpr double kKluFastestFlopsPerSecond = 5.0e9;
// Growth of an implicit method's steps per factor 100 in tolerance, before it has two runs
// (the stiff bed at 25,088 particles: 2.5, 2.1, 1.8, 1.9).
inline constexpr double kDefaultGrowthPer100 = 2.0;

struct RunForecast {
  double wall_time_s = std::numeric_limits<double>::quiet_NaN();  // NaN: no prediction
  std::string basis;  // how it was predicted, for the report
  bool known() const { return wall_time_s == wall_time_s; }
};

class AccuracyRunForecaster {
 public:
  // `klu`: the cost of one factorisation of the study's system (timed, or analysed only); empty
  // when no klu method is studied (klu runs then get no prediction).
  explicit AccuracyRunForecaster(std::optional<thermal::KluFactorisationCost> klu = {});

  // The run of `method`/`solver` at `rtol`, from the finished runs in `done`.
  RunForecast implicit_run(const std::string& method, const std::string& solver, double rtol,
                           const std::vector<AccuracyRun>& done) const;

  // An explicit rung of `work` units (steps x (particles + edges + wall edges)); the seconds per
  // unit from the smallest-step explicit run in `done` with `work_per_step` units a step, else
  // `probe_seconds_per_unit` (NaN: no prediction).
  RunForecast explicit_run(double work, double work_per_step, const std::vector<AccuracyRun>& done,
                           double probe_seconds_per_unit) const;

 private:
  std::optional<thermal::KluFactorisationCost> klu_;
};

}  // namespace tmdem::coupling
