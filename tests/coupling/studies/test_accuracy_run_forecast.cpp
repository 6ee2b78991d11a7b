// The accuracy study's predictions of a run's wall time (coupling/studies/AccuracyRunForecast.h),
// each against the rule's arithmetic worked by hand on made-up finished runs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "coupling/studies/AccuracyRunForecast.h"

namespace tmdem::coupling {
namespace {

AccuracyRun finished(const std::string& method, const std::string& solver, double rtol,
                     double wall_s, long steps, long setups, long rhs) {
  AccuracyRun r;
  r.method = method;
  r.linear_solver = solver;
  r.parameter = rtol;
  r.wall_time_s = wall_s;
  r.steps = steps;
  r.linear_setups = setups;
  r.rhs_evals = rhs;
  return r;
}

// One KLU factorisation of 2 s and one solve of 0.1 s, as if timed.
thermal::KluFactorisationCost timed_klu() {
  thermal::KluFactorisationCost cost;
  cost.flops = 1e9;
  cost.factor_nonzeros = 1e6;
  cost.factorisation_s = 2.0;
  cost.solve_s = 0.1;
  return cost;
}

TEST(AccuracyRunForecast, AnIterativeMethodsFirstRunIsNotPredicted) {
  const AccuracyRunForecaster forecaster(timed_klu());
  EXPECT_FALSE(forecaster.implicit_run("cvode", "pcg", 1e-2, {}).known());
}

TEST(AccuracyRunForecast, KlusFirstRunTakesItsSiblingsCounts) {
  const AccuracyRunForecaster forecaster(timed_klu());
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 0.5, 10, 5, 20),
                                      finished("ida", "pcg", 1e-2, 9.0, 10, 1, 1)};
  // 5 factorisations of 2 s, 20 solves of 0.1 s, and the rest as cvode/pcg spent it.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "klu", 1e-2, done).wall_time_s,
                   5 * 2.0 + 20 * 0.1 + 0.5);
}

TEST(AccuracyRunForecast, KlusNextRunGrowsAsItsSiblingsModelDid) {
  const AccuracyRunForecaster forecaster(timed_klu());
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 0.5, 10, 5, 20),
                                      finished("cvode", "pcg", 1e-4, 0.9, 25, 8, 40),
                                      finished("cvode", "klu", 1e-2, 11.0, 10, 5, 20)};
  // The model of cvode/pcg's counts: 5 x 2 + 20 x 0.1 = 12 s at 1e-2, 8 x 2 + 40 x 0.1 = 20 s at
  // 1e-4; cvode/klu's 11 s grow by 20 / 12.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "klu", 1e-4, done).wall_time_s,
                   11.0 * 20.0 / 12.0);
}

TEST(AccuracyRunForecast, AnIterativeRunGrowsByRightHandSidesElseByItsSteps) {
  const AccuracyRunForecaster forecaster;
  std::vector<AccuracyRun> done{finished("ida", "amg", 1e-2, 1.0, 10, 4, 20),
                                finished("ida", "pcg", 1e-2, 0.7, 10, 4, 22),
                                finished("ida", "pcg", 1e-4, 1.3, 25, 6, 55)};
  // ida/pcg's right-hand sides from 1e-2 to 1e-4: 22 -> 55, so ida/amg's 1 s x 55 / 22.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("ida", "amg", 1e-4, done).wall_time_s, 55.0 / 22.0);
  // No sibling at 1e-6: ida/pcg's own steps grew 10 -> 25 per factor 100, so its 1.3 s x 2.5.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("ida", "pcg", 1e-6, done).wall_time_s, 1.3 * 2.5);
  // Two factors of 100 beyond its tightest run: 2.5^2.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("ida", "pcg", 1e-8, done).wall_time_s, 1.3 * 6.25);
  // One run of its own: kDefaultGrowthPer100.
  done.erase(done.begin() + 2);
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("ida", "pcg", 1e-4, done).wall_time_s,
                   0.7 * kDefaultGrowthPer100);
}

TEST(AccuracyRunForecast, ATighterRunIsNeverPredictedCheaper) {
  const AccuracyRunForecaster forecaster;
  // The sibling's right-hand sides fell from 1e-2 to 1e-4: the ratio is held at 1.
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 0.5, 10, 5, 40),
                                      finished("cvode", "pcg", 1e-4, 0.4, 12, 5, 30),
                                      finished("cvode", "amg", 1e-2, 2.0, 10, 5, 40)};
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "amg", 1e-4, done).wall_time_s, 2.0);
}

TEST(AccuracyRunForecast, AnUntimedFactorisationGivesALowerBound) {
  thermal::KluFactorisationCost analysed;  // the analysis alone: no timing
  analysed.flops = 1e13;
  analysed.factor_nonzeros = 1e9;
  const AccuracyRunForecaster forecaster(analysed);
  // No counts: one factorisation at the fastest rate measured.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "klu", 1e-2, {}).wall_time_s,
                   1e13 / kKluFastestFlopsPerSecond);
  // With cvode/pcg's 6 setups: six of them.
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 30.0, 12, 6, 20)};
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "klu", 1e-2, done).wall_time_s,
                   6 * 1e13 / kKluFastestFlopsPerSecond);
}

TEST(AccuracyRunForecast, KluWithoutASiblingAtItsToleranceGrowsTheSiblingsTightestRun) {
  const AccuracyRunForecaster forecaster(timed_klu());
  // cvode/pcg stopped at 1e-4 (its steps grew 10 -> 40 per factor 100); cvode/klu never ran.
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 0.5, 10, 5, 20),
                                      finished("cvode", "pcg", 1e-4, 1.0, 40, 8, 50)};
  // At 1e-6: cvode/pcg's 1e-4 counts x 4: 32 setups, 200 solves, and its 1 s x 4 besides.
  EXPECT_DOUBLE_EQ(forecaster.implicit_run("cvode", "klu", 1e-6, done).wall_time_s,
                   32 * 2.0 + 200 * 0.1 + 4.0);
}

TEST(AccuracyRunForecast, KluIsNotPredictedWithoutItsCost) {
  const AccuracyRunForecaster forecaster;  // no klu method was studied
  const std::vector<AccuracyRun> done{finished("cvode", "pcg", 1e-2, 0.5, 10, 5, 20)};
  EXPECT_FALSE(forecaster.implicit_run("cvode", "klu", 1e-2, done).known());
}

TEST(AccuracyRunForecast, ExplicitRungsCostTheirWorkAtTheFinestRunsRate) {
  const AccuracyRunForecaster forecaster;
  const double work_per_step = 100.0;  // particles + edges + wall edges
  const std::vector<AccuracyRun> done{
      finished("explicit", "none", 1e-2, 0.5, 100, 0, 100),
      finished("explicit", "none", 2.5e-3, 2.0, 400, 0, 400)};
  // The finest run: 2 s for 400 x 100 units, 5e-5 s a unit.
  EXPECT_DOUBLE_EQ(forecaster.explicit_run(1e6, work_per_step, done, 1.0).wall_time_s, 50.0);
  // No explicit run yet: the probe's rate; no probe either: no prediction.
  EXPECT_DOUBLE_EQ(forecaster.explicit_run(1e6, work_per_step, {}, 3e-6).wall_time_s, 3.0);
  EXPECT_FALSE(forecaster.explicit_run(1e6, work_per_step, {}, std::nan("")).known());
}

}  // namespace
}  // namespace tmdem::coupling
