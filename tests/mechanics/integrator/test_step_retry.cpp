// Retaking an unconverged step in parts (NscdParameters::retry_parts): the try that stands is
// bit for bit the parts an integrator without retries takes from the same start, so the tries
// thrown away leave nothing behind (positions, velocities, warm starts, candidate table, the
// first step's static warm start); their sweeps are counted apart; a converged step is never
// retaken; retries that fail are cut and come back after converged steps; the parameter is
// checked.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/integrator/ToleranceSchedule.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace retry_test {

constexpr double kWidth = 0.008;  // m, settled_disk_pile's box

// A new integrator on the settled pile's disks (the same box and materials as
// settled_disk_pile), its upper half pushed sideways at `push_m_per_s` so the steps have
// something to solve: its first step has contacts and a static warm start pending.
NscdIntegrator pushed_from(const NscdIntegrator& settled, double push_m_per_s, const NscdParameters& parameters) {
  ParticleSet set = settled.particles();
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.position[i].y() > 4e-3) set.velocity[i] = Eigen::Vector3d(push_m_per_s, 0.0, 0.0);
  auto walls = box_walls(kWidth, kWidth, 2);
  for (std::size_t w = 1; w < walls.size(); ++w) walls[w].material = 1;
  return NscdIntegrator(std::move(set), {steel(0.5), steel(0.0)}, walls, Eigen::Vector3d(0, -kG, 0), 2,
                        parameters);
}

NscdIntegrator pile_from(const NscdIntegrator& settled, int retry_parts, int max_iterations,
                         double tolerance) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = tolerance;
  parameters.max_iterations = max_iterations;
  parameters.retry_parts = retry_parts;
  return pushed_from(settled, 0.02, parameters);
}

void expect_same_state(const NscdIntegrator& a, const NscdIntegrator& b, const char* where) {
  ASSERT_EQ(a.particles().size(), b.particles().size());
  for (std::size_t i = 0; i < a.particles().size(); ++i) {
    EXPECT_EQ(a.particles().position[i], b.particles().position[i]) << where << ", particle " << i;
    EXPECT_EQ(a.particles().velocity[i], b.particles().velocity[i]) << where << ", particle " << i;
    EXPECT_EQ(a.particles().angular_velocity[i], b.particles().angular_velocity[i])
        << where << ", particle " << i;
  }
  for (std::size_t w = 0; w < a.walls().size(); ++w) {
    EXPECT_EQ(a.walls()[w].point, b.walls()[w].point) << where << ", wall " << w;
    EXPECT_EQ(a.walls()[w].velocity_m_per_s, b.walls()[w].velocity_m_per_s) << where << ", wall " << w;
  }
  ASSERT_EQ(a.contacts().size(), b.contacts().size()) << where;
  for (std::size_t k = 0; k < a.contacts().size(); ++k) {
    EXPECT_EQ(a.contacts()[k].normal_impulse_Ns, b.contacts()[k].normal_impulse_Ns) << where;
    EXPECT_EQ(a.contacts()[k].tangential_force_N, b.contacts()[k].tangential_force_N) << where;
  }
}

// The settled pile's upper half pushed sideways at `push_m_per_s`, the tolerance schedule on
// (tight 1e-12, fall_tolerance 1e-3, at once: tighten_steps 1) with `fall_speed_m_per_s`: a
// collapse is judged at a tenth of it (ToleranceSchedule::kCollapseSpeedFraction).
NscdIntegrator pushed_pile(const NscdIntegrator& settled, double push_m_per_s, double fall_speed_m_per_s,
                           int retry_parts, double fall_tolerance = 1e-3) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-12;
  parameters.fall_tolerance = fall_tolerance;
  parameters.fall_speed = fall_speed_m_per_s;
  parameters.tighten_steps = 1;
  parameters.max_iterations = 3000;
  parameters.retry_parts = retry_parts;
  return pushed_from(settled, push_m_per_s, parameters);
}

}  // namespace retry_test

using namespace retry_test;

TEST(StepRetry, AnUnconvergedStepStandsAsItsPartsWithNothingLeftOfTheTriesThrownAway) {
  const NscdIntegrator settled = settled_disk_pile();
  // Two sweeps a solve at 1e-8: no try converges, so each step is retaken in 2, then 4 parts.
  constexpr int kSweeps = 2;
  const double h = settled.parameters().time_step;
  NscdIntegrator retried = pile_from(settled, 4, kSweeps, 1e-8);
  NscdIntegrator quarters = pile_from(settled, 1, kSweeps, 1e-8);
  // The tries thrown away, as an integrator without retries takes them from the same start.
  NscdIntegrator whole = pile_from(settled, 1, kSweeps, 1e-8);
  NscdIntegrator halves = pile_from(settled, 1, kSweeps, 1e-8);

  const StepReport report = retried.step(h);
  const StepReport whole_report = whole.step(h);
  const StepReport half_report = merged(halves.step(0.5 * h), halves.step(0.5 * h));
  StepReport quarter_report = quarters.step(0.25 * h);
  for (int part = 1; part < 4; ++part) quarter_report = merged(quarter_report, quarters.step(0.25 * h));
  ASSERT_FALSE(whole_report.converged);
  ASSERT_FALSE(half_report.converged);
  ASSERT_FALSE(quarter_report.converged);
  EXPECT_FALSE(report.converged);  // the last try stands, converged or not
  EXPECT_EQ(report.retry_parts, 4);
  EXPECT_EQ(report.sweeps, quarter_report.sweeps);
  EXPECT_EQ(report.discarded_sweeps, whole_report.sweeps + half_report.sweeps);
  EXPECT_GT(report.discarded_sweeps, 0);
  expect_same_state(retried, quarters, "first step");
  // Each part counts as a step; the retry once; the thrown-away sweeps apart from total_sweeps.
  EXPECT_EQ(retried.stats().steps, 4);
  EXPECT_EQ(retried.stats().retried_steps, 1);
  EXPECT_EQ(retried.stats().discarded_sweeps, report.discarded_sweeps);
  EXPECT_EQ(retried.stats().total_sweeps, quarters.stats().total_sweeps);
  EXPECT_EQ(retried.stats().unconverged_steps, quarters.stats().unconverged_steps);

  // A step from the middle of a run (warm starts and candidate table of the step before). The
  // first step failed through its retries, so this one is retaken in at most 2 parts (the
  // budget: RetriesThatFailAreCutAndComeBackAfterConvergedSteps).
  const StepReport second = retried.step(h);
  for (int part = 0; part < 2; ++part) quarters.step(0.5 * h);
  EXPECT_EQ(second.retry_parts, 2);
  expect_same_state(retried, quarters, "second step");
  EXPECT_EQ(retried.stats().steps, 6);
  EXPECT_EQ(retried.stats().retried_steps, 2);
  EXPECT_EQ(retried.stats().energy_change_J, quarters.stats().energy_change_J);
}

TEST(StepRetry, AConvergedStepIsNeverRetaken) {
  const NscdIntegrator settled = settled_disk_pile();
  NscdIntegrator retried = pile_from(settled, 8, 10000, 1e-4);
  NscdIntegrator plain = pile_from(settled, 1, 10000, 1e-4);
  for (int step = 0; step < 20; ++step) {
    const StepReport report = retried.step();
    ASSERT_TRUE(plain.step().converged) << "step " << step << ": the test needs converged steps";
    EXPECT_EQ(report.retry_parts, 0);
    EXPECT_EQ(report.discarded_sweeps, 0);
  }
  expect_same_state(retried, plain, "20 converged steps");
  EXPECT_EQ(retried.stats().retried_steps, 0);
  EXPECT_EQ(retried.stats().steps, 20);
  EXPECT_EQ(retried.stats().unconverged_time_steps, 0);
}

TEST(StepRetry, RetriesThatFailAreCutAndComeBackAfterConvergedSteps) {
  const NscdIntegrator settled = settled_disk_pile();
  const double h = settled.parameters().time_step;
  // Every try fails (two sweeps a solve): the first step is retaken up to 8 parts, the next up
  // to 4, then 2, then not at all.
  NscdIntegrator failing = pile_from(settled, 8, 2, 1e-8);
  for (const int expected_parts : {8, 4, 2, 0, 0}) {
    const StepReport report = failing.step(h);
    ASSERT_FALSE(report.converged);
    EXPECT_EQ(report.retry_parts, expected_parts);
    EXPECT_EQ(report.discarded_sweeps > 0, expected_parts > 0);
  }
  EXPECT_EQ(failing.stats().retried_steps, 3);
  EXPECT_EQ(failing.stats().steps, 8 + 4 + 2 + 1 + 1);
  // Every part failed: unconverged_steps counts each, unconverged_time_steps (one warning
  // each in a run) the five steps of h.
  EXPECT_EQ(failing.stats().unconverged_steps, 8 + 4 + 2 + 1 + 1);
  EXPECT_EQ(failing.stats().unconverged_time_steps, 5);
  const MechanicsState cut = failing.save_state();
  EXPECT_EQ(cut.retry_limit, 1);
  EXPECT_EQ(cut.stats.unconverged_time_steps, 5);  // carried by the state, as the others

  // The same bed solved to convergence from there (its state carries the budget): every ten
  // converged steps in a row double it back, up to retry_parts.
  NscdIntegrator converging = pile_from(settled, 8, 10000, 1e-3);
  converging.restore_state(cut);
  for (const int expected_limit : {2, 4, 8, 8}) {
    for (int step = 0; step < NscdIntegrator::kRetryRecoverSteps; ++step)
      ASSERT_TRUE(converging.step(h).converged) << "the test needs converged steps";
    EXPECT_EQ(converging.save_state().retry_limit, expected_limit);
  }
}

// 6 steel spheres stacked on the floor and a 5 g piston under 2 N falling 10 R onto them,
// landing at about 2.5 m/s: the landing step is taken in equal parts (test_piston.cpp).
NscdIntegrator landing_column(int retry_parts, int max_iterations, double tolerance = 1e-10,
                              bool fallback_on_last_try = false) {
  ParticleSet set;
  for (int k = 0; k < 6; ++k)
    set.add(Eigen::Vector3d(0, kRadius * (2 * k + 1), 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  Wall piston = Wall::through({0, 12 * kRadius + 10 * kRadius, 0}, {0, -1, 0}, 0);
  piston.make_piston(0.005, 2.0);
  NscdParameters parameters = nlgs_parameters();
  parameters.solver = "nncg_ipm";
  parameters.tolerance = tolerance;
  parameters.max_iterations = max_iterations;
  parameters.retry_parts = retry_parts;
  parameters.fallback_on_last_try = fallback_on_last_try;
  return NscdIntegrator(std::move(set), {steel(0.0)},
                        {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston,
                         Wall::through({-kRadius, 0, 0}, {1, 0, 0}, 0),
                         Wall::through({kRadius, 0, 0}, {-1, 0, 0}, 0)},
                        Eigen::Vector3d(0, -kG, 0), 3, parameters);
}

// The default solver's later stages, counted step by step: nncg cut to 10 sweeps hands the
// landing column's unconverged solves on to the interior point. With no retries, every step's
// report counts the solves it handed on (at most one per part), their work is the sweeps beyond
// nncg's 3 per solve, and the run's counts are the sum of the steps'.
TEST(FallbackCounts, EverySolveHandedOnIsCountedWithTheStageThatEndedIt) {
  constexpr int kSweeps = 10;
  constexpr double kTolerance = 1e-6;
  NscdIntegrator sim = landing_column(1, kSweeps, kTolerance);
  ASSERT_TRUE(sim.solver().has_fallback());
  const double h = sim.parameters().time_step;
  FallbackCounts sum;
  std::int64_t converged_handed_on = 0;
  for (int step = 0; step < 60; ++step) {
    const std::int64_t steps_before = sim.stats().steps, sweeps_before = sim.stats().total_sweeps;
    const StepReport report = sim.step(h);
    const std::int64_t parts = sim.stats().steps - steps_before;
    const FallbackCounts& f = report.fallback;
    ASSERT_LE(f.solves, parts) << "step " << step;
    EXPECT_LE(f.converged_by_second + f.converged_by_first_again + f.converged_by_sweeps + f.within_when_handed_on,
              f.solves);
    if (parts == 1 && f.solves == 1) {
      // nncg ran its 3 sweeps unconverged; the rest of the step's sweeps are the later stages'.
      EXPECT_EQ(f.sweeps, report.sweeps - kSweeps) << "step " << step;
      EXPECT_EQ(f.first_sweeps, kSweeps) << "step " << step;
      EXPECT_GT(f.seconds, 0.0);
      EXPECT_GT(f.first_seconds, 0.0);
      // The stage that ended it converged it exactly when the step converged (unless it was
      // within the tolerance by Siconos' measure when handed on, counted apart).
      if (f.within_when_handed_on == 0)
        EXPECT_EQ(f.converged_by_second + f.converged_by_first_again + f.converged_by_sweeps,
                  report.converged ? 1 : 0) << "step " << step;
    }
    if (f.solves == 0) {
      EXPECT_LE(sim.stats().total_sweeps - sweeps_before, kSweeps * parts) << "step " << step;
      EXPECT_EQ(f.sweeps, 0);
      EXPECT_EQ(f.first_sweeps, 0);
    }
    converged_handed_on += f.converged_by_second + f.converged_by_first_again + f.converged_by_sweeps;
    sum += f;
  }
  const FallbackCounts& run = sim.stats().fallback;
  EXPECT_EQ(run.solves, sum.solves);
  EXPECT_EQ(run.converged_by_second, sum.converged_by_second);
  EXPECT_EQ(run.converged_by_first_again, sum.converged_by_first_again);
  EXPECT_EQ(run.converged_by_sweeps, sum.converged_by_sweeps);
  EXPECT_EQ(run.within_when_handed_on, sum.within_when_handed_on);
  EXPECT_EQ(run.sweeps, sum.sweeps);
  EXPECT_DOUBLE_EQ(run.seconds, sum.seconds);
  EXPECT_EQ(run.first_sweeps, sum.first_sweeps);
  EXPECT_DOUBLE_EQ(run.first_seconds, sum.first_seconds);
  // The test acts: solves were handed on, and most converged there (37 of 40 when written).
  EXPECT_GE(run.solves, 10);
  EXPECT_GE(converged_handed_on, run.solves / 2);

  // With retries, the tries thrown away count too: StepRetry.TheFallbackRunsOnlyOnAStepsLastTry.
}

// fallback_on_last_try: the later stages run only on a try no retry follows. The landing column
// at 1e-10, nncg cut to 3 sweeps, retaken up to 8 parts: every solve handed on is in a try that
// stands (the run's counts equal the standing steps'), where without the option the thrown
// tries hand on too; the retried steps' standing tries hand on, and a step that converged as
// first taken handed nothing on (its try was not the last possible).
TEST(StepRetry, TheFallbackRunsOnlyOnAStepsLastTry) {
  for (const bool last_only : {true, false}) {
    SCOPED_TRACE(last_only ? "fallback_on_last_try" : "every try");
    NscdIntegrator sim = landing_column(8, 3, 1e-10, last_only);
    const double h = sim.parameters().time_step;
    FallbackCounts standing;
    std::int64_t retried_steps = 0;
    for (int step = 0; step < 60; ++step) {
      const StepReport report = sim.step(h);
      standing += report.fallback;
      if (report.retry_parts > 0) ++retried_steps;
      if (last_only && report.retry_parts == 0 && report.converged)
        EXPECT_EQ(report.fallback.solves, 0) << "step " << step;
    }
    ASSERT_GT(retried_steps, 0) << "the test needs a retried step";
    ASSERT_GT(standing.solves, 0) << "the test needs solves handed on";
    if (last_only) {
      EXPECT_EQ(sim.stats().fallback.solves, standing.solves);
      EXPECT_EQ(sim.stats().fallback.sweeps, standing.sweeps);
    } else {
      // A try is thrown away only unconverged, so its solve was handed on: each retried step
      // adds at least one, and its sweeps.
      EXPECT_GE(sim.stats().fallback.solves, standing.solves + retried_steps);
      EXPECT_GT(sim.stats().fallback.sweeps, standing.sweeps);
    }
  }
}

TEST(StepRetry, ALandingTakenInPartsIsRetakenInShorterParts) {
  // A landing taken in P parts and retaken in 2 parts of h / 2 would repeat its first try part
  // for part; it is retaken in 2 P parts of h / (2 P).
  constexpr int kSweeps = 3;
  NscdIntegrator retried = landing_column(2, kSweeps);
  NscdIntegrator plain = landing_column(1, kSweeps);
  const double h = retried.parameters().time_step;
  for (int step = 0; step < 100; ++step) {
    const MechanicsState start = plain.save_state();
    const std::int64_t steps_before = plain.stats().steps;
    const StepReport report = retried.step(h);
    const StepReport first_try = plain.step(h);
    if (report.retry_parts == 0) {
      ASSERT_TRUE(first_try.converged) << "step " << step;
      continue;
    }
    ASSERT_FALSE(first_try.converged);
    const int first_parts = int(plain.stats().steps - steps_before);
    ASSERT_GT(first_parts, 1) << "step " << step << ": the first retaken step should be the landing";
    EXPECT_EQ(report.retry_parts, 2 * first_parts);
    NscdIntegrator parts = landing_column(1, kSweeps);
    parts.restore_state(start);
    for (int part = 0; part < 2 * first_parts; ++part) parts.step(h / (2 * first_parts));
    expect_same_state(retried, parts, "the landing retaken");
    return;
  }
  FAIL() << "no step was retaken in 100";
}

TEST(StepRetry, PartsOutsideTheirRangeAreRefused) {
  const NscdIntegrator settled = settled_disk_pile();
  for (const int parts : {0, NscdParameters::kMaxRetryParts + 1}) {
    try {
      pile_from(settled, parts, 100, 1e-6);
      ADD_FAILURE() << "retry_parts = " << parts << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("retry_parts"), std::string::npos) << e.what();
    }
  }
}

// A step that stalls at the tight tolerance while the bed moves at a tenth of fall_speed or more
// (a collapse; ToleranceSchedule::begin_collapse) is taken again whole at fall_tolerance: the step
// that stands is bit for bit the step of an integrator whose fall_speed is that tenth (falling
// from its first step, so solved at fall_tolerance), the first try's sweeps are thrown away, and
// the phase is Collapsing until the fastest particle is slower than the tenth; then tight again.
TEST(StepRetry, AStalledStepOfACollapsingBedIsRetakenAtTheFallTolerance) {
  const NscdIntegrator settled = settled_disk_pile();
  const double h = settled.parameters().time_step;
  constexpr double kPush = 0.02, kFallSpeed = 0.1;  // m/s: the push is above a tenth, below fall_speed
  NscdIntegrator collapsing = pushed_pile(settled, kPush, kFallSpeed, 2);
  NscdIntegrator tight = pushed_pile(settled, kPush, kFallSpeed, 1);  // the first try alone
  NscdIntegrator falling = pushed_pile(settled, kPush, 0.1 * kFallSpeed, 1);
  const StepReport first_try = tight.step(h);
  ASSERT_FALSE(first_try.converged) << "the test needs a step that fails at 1e-12";
  ASSERT_FALSE(first_try.fall);
  const StepReport fallen = falling.step(h);
  ASSERT_TRUE(fallen.fall);
  ASSERT_TRUE(fallen.converged) << "the test needs a step that converges at 1e-3: " << fallen.sweeps << " sweeps, " << fallen.residual << ", " << fallen.siconos_residual;

  const StepReport report = collapsing.step(h);
  EXPECT_TRUE(report.converged);
  EXPECT_TRUE(report.fall);
  EXPECT_TRUE(report.collapse);
  EXPECT_EQ(report.tolerance, 1e-3);
  EXPECT_EQ(report.retry_parts, 1);
  EXPECT_EQ(report.sweeps, fallen.sweeps);
  EXPECT_EQ(report.discarded_sweeps, first_try.sweeps);
  expect_same_state(collapsing, falling, "the collapsing step");
  EXPECT_EQ(collapsing.tolerance_schedule().phase(), ToleranceSchedule::Phase::Collapsing);
  EXPECT_EQ(collapsing.stats().retried_steps, 1);
  EXPECT_EQ(collapsing.stats().steps, 1);
  EXPECT_EQ(collapsing.stats().unconverged_steps, 0);
  // The phase is in the state a checkpoint carries.
  EXPECT_EQ(collapsing.save_state().tolerance_schedule.phase, ToleranceSchedule::Phase::Collapsing);

  // Still collapsing while the fastest moves at the tenth or faster; landed, and tight, once
  // every particle is slower.
  collapsing.particles().velocity[0] = Eigen::Vector3d(0.0, 0.5 * kFallSpeed, 0.0);
  EXPECT_EQ(collapsing.step(h).tolerance, 1e-3);
  for (auto& v : collapsing.particles().velocity) v.setZero();
  const StepReport landed = collapsing.step(h);
  EXPECT_FALSE(landed.fall);
  EXPECT_EQ(landed.tolerance, 1e-12);
  EXPECT_EQ(collapsing.tolerance_schedule().phase(), ToleranceSchedule::Phase::Landed);
}

// Slower than a tenth of fall_speed, at the start and at the end of its first try, the bed is not
// collapsing: the stalled step is retaken in parts, at the tight tolerance, as without the
// schedule.
TEST(StepRetry, AStalledStepOfASlowBedIsRetakenInParts) {
  const NscdIntegrator settled = settled_disk_pile();
  const double h = settled.parameters().time_step;
  NscdIntegrator slow = pushed_pile(settled, 0.005, 0.1, 2);  // 0.005 m/s: below 0.01
  const StepReport report = slow.step(h);
  EXPECT_FALSE(report.collapse);
  EXPECT_FALSE(report.fall);
  EXPECT_EQ(report.tolerance, 1e-12);
  EXPECT_EQ(report.retry_parts, 2);
  EXPECT_EQ(slow.tolerance_schedule().phase(), ToleranceSchedule::Phase::Before);
}

// With fall_tolerance equal to the tolerance a collapse would repeat the failed try: the stalled
// step of the same collapsing bed is retaken in parts, as without a schedule.
TEST(StepRetry, NoCollapseWhereTheFallToleranceIsNoLooser) {
  const NscdIntegrator settled = settled_disk_pile();
  const double h = settled.parameters().time_step;
  NscdIntegrator equal = pushed_pile(settled, 0.02, 0.1, 2, 1e-12);
  NscdIntegrator tight = pushed_pile(settled, 0.02, 0.1, 1, 1e-12);  // the first try alone
  const StepReport first_try = tight.step(h);
  ASSERT_FALSE(first_try.converged);
  const StepReport report = equal.step(h);
  EXPECT_FALSE(report.collapse);
  EXPECT_EQ(report.retry_parts, 2);
  EXPECT_EQ(report.discarded_sweeps, first_try.sweeps);  // the first try only, taken once
  EXPECT_EQ(equal.stats().collapse_steps, 0);
  EXPECT_EQ(equal.tolerance_schedule().phase(), ToleranceSchedule::Phase::Before);
}

TEST(StepRetry, AStepInPartsNamesTheToleranceItsUnconvergedPartMissed) {
  // A first part unconverged at 1e-5, the next converged at the fall's 1e-4 (the schedule
  // changed between them): the step is unconverged against 1e-5, not 1e-4.
  StepReport tight, loose;
  tight.converged = false;
  tight.tolerance = 1e-5;
  tight.siconos_residual = 9.97e-5;
  loose.converged = true;
  loose.tolerance = 1e-4;
  loose.siconos_residual = 5e-5;
  const StepReport step = merged(tight, loose);
  EXPECT_FALSE(step.converged);
  EXPECT_EQ(step.tolerance, 1e-5);
  EXPECT_EQ(step.siconos_residual, 9.97e-5);
  MechanicsStats stats;
  stats.add(step);
  // By the counters' own rule the merged report is above the tolerance it missed (a run's
  // counters add each part as it is taken: NscdIntegrator::step).
  EXPECT_EQ(stats.siconos_unconverged_steps, 1);
  // Both unconverged: the tighter; both converged: the last part's, as before.
  StepReport loose_failed = loose;
  loose_failed.converged = false;
  EXPECT_EQ(merged(loose_failed, tight).tolerance, 1e-5);
  EXPECT_EQ(merged(loose_failed, tight).converged, false);
  StepReport tight_met = tight;
  tight_met.converged = true;
  EXPECT_EQ(merged(tight_met, loose).tolerance, 1e-4);
  EXPECT_EQ(merged(loose, loose_failed).tolerance, 1e-4);
}

namespace retry_test {

// The parts a step of h was taken in at the end: its retry's, else its kept parts, else 1.
int parts_taken(const StepReport& report) {
  if (report.retry_parts > 0) return report.retry_parts;
  return report.start_parts > 0 ? report.start_parts : 1;
}

}  // namespace retry_test

// retry_keep_steps: after a step that converged only in P parts the next steps start in P parts,
// and every retry_keep_steps converged steps in a row halve P, down to whole steps. The steps
// stand as the parts an integrator without retries takes from the same start, bit for bit; the
// kept parts go through a checkpoint.
TEST(StepRetry, StepsAfterARetryStartInItsPartsUntilEnoughConvergeInARow) {
  const NscdIntegrator settled = settled_disk_pile();
  const double h = settled.parameters().time_step;
  // The pile's upper half pushed at 0.2 m/s, solved to 1e-5 within 3,000 sweeps: some whole
  // steps stall and converge in 4 or 8 parts, every step converges in the end.
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-5;
  parameters.max_iterations = 3000;
  parameters.retry_parts = 8;
  parameters.retry_keep_steps = 2;
  NscdIntegrator kept = pushed_from(settled, 0.2, parameters);
  NscdParameters plain_parameters = parameters;
  plain_parameters.retry_parts = 1;
  NscdIntegrator plain = pushed_from(settled, 0.2, plain_parameters);

  constexpr int kSteps = 20, kCheckpointStep = 8;
  int expected_start = 1, converged_at_start = 0, kept_steps = 0, halvings = 0;
  MechanicsState checkpoint;
  std::vector<StepReport> after_checkpoint;
  for (int step = 0; step < kSteps; ++step) {
    if (step == kCheckpointStep) checkpoint = kept.save_state();
    const StepReport report = kept.step(h);
    ASSERT_TRUE(report.converged) << "step " << step << ": the test needs converged steps";
    EXPECT_EQ(std::max(1, report.start_parts), expected_start) << "step " << step;
    if (report.start_parts > 1) ++kept_steps;
    // A retry goes on from the kept parts: finer than them.
    if (report.retry_parts > 0) EXPECT_GT(report.retry_parts, expected_start) << "step " << step;
    const int parts = parts_taken(report);
    for (int part = 0; part < parts; ++part) plain.step(h / double(parts));
    expect_same_state(kept, plain, "a step in its kept or retried parts");
    if (step >= kCheckpointStep) after_checkpoint.push_back(report);
    // The rule, from the reports alone.
    if (report.retry_parts > 0) {
      expected_start = report.retry_parts;
      converged_at_start = 0;
    } else if (expected_start > 1 && ++converged_at_start == parameters.retry_keep_steps) {
      expected_start /= 2;
      converged_at_start = 0;
      ++halvings;
    }
  }
  // Not a rule that never acted: steps started in kept parts, and those were halved back.
  EXPECT_GE(kept_steps, 5);
  EXPECT_GE(halvings, 3);
  EXPECT_EQ(kept.stats().kept_parts_steps, kept_steps);

  // From the checkpoint, the same steps in the same parts.
  NscdIntegrator restarted = pushed_from(settled, 0.2, parameters);
  restarted.restore_state(checkpoint);
  for (std::size_t k = 0; k < after_checkpoint.size(); ++k) {
    const StepReport report = restarted.step(h);
    EXPECT_EQ(report.start_parts, after_checkpoint[k].start_parts) << "step " << kCheckpointStep + k;
    EXPECT_EQ(report.retry_parts, after_checkpoint[k].retry_parts) << "step " << kCheckpointStep + k;
  }
  expect_same_state(restarted, kept, "restarted from a checkpoint");

  // Off (0): every step starts whole.
  parameters.retry_keep_steps = 0;
  NscdIntegrator whole = pushed_from(settled, 0.2, parameters);
  for (int step = 0; step < 12; ++step) EXPECT_EQ(whole.step(h).start_parts, 0) << "step " << step;
  EXPECT_EQ(whole.stats().kept_parts_steps, 0);
}
