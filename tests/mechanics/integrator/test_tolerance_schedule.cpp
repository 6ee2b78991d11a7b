// The tolerance schedule (mechanics/integrator/ToleranceSchedule.h, NscdParameters::fall_tolerance and
// fall_speed): which tolerance each step uses, checked against a sphere dropped onto a floor
// whose speeds are known in closed form; that the tolerance in force is the one the solver
// stops at; and that a restored integrator continues bit for bit across the switch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "mechanics/SameBits.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/integrator/ToleranceSchedule.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace {

using tmdem::mechanics::test::same_bits;

constexpr double kStep = 1e-3;  // s

// One sphere of radius kRadius whose gap to the floor is g h^2 n^2 / 2: in free fall under the
// theta = 1/2 scheme (x_k = x_0 - g h^2 k^2 / 2 exactly, v_k = -k h g) it reaches the floor
// after n steps. The gap is predicted one step ahead (P = gap + h u_n / 2; NscdIntegrator.h),
// so the floor acts in step n already: at the start of step n the gap is g h^2 (2n - 1) / 2
// and the speed (n - 1) h g, P = g h^2 n / 2 > 0, and the inelastic condition
// u_n(v+) + P / h = 0 gives v+ = -n h g / 2 (half the free-fall speed), leaving the gap P / 2.
// In step n + 1, P = P / 2 - h (n h g / 2) / 2 = 0: the sphere stops (v+ = 0) and rests.
// In step n - 1 the floor does not act (P = (3n/2 - 1) g h^2, free U_n = n h g / 2 > 0).
// So the speed at the start of step k is (k - 1) h g for k <= n, n h g / 2 at k = n + 1 and
// 0 from k = n + 2 on.
NscdIntegrator dropped_sphere(int n, NscdParameters parameters) {
  parameters.time_step = kStep;
  ParticleSet set;
  const double gap = kG * kStep * kStep * n * n / 2.0;
  set.add(Eigen::Vector3d(0.0, kRadius + gap, 0.0), kRadius, sphere_mass(kRadius, kDensity), 0);
  return NscdIntegrator(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                        Eigen::Vector3d(0, -kG, 0), 3, parameters);
}

NscdParameters schedule(double tolerance, double fall_tolerance, double fall_speed) {
  NscdParameters p = nlgs_parameters();
  p.tolerance = tolerance;
  p.fall_tolerance = fall_tolerance;
  p.fall_speed = fall_speed;
  p.tighten_steps = 1;  // the switch at once; the ramp has tests of its own (tighten_steps > 1)
  return p;
}

// A sphere resting on a floor (wall 0) and a 10 g piston (wall 1) of load `load_N` released
// half a radius above it.
NscdIntegrator piston_over_sphere(double load_N, const NscdParameters& parameters) {
  ParticleSet set;
  set.add(Eigen::Vector3d(0.0, kRadius, 0.0), kRadius, sphere_mass(kRadius, kDensity), 0);
  Wall piston = Wall::through({0.0, 2.5 * kRadius, 0.0}, {0.0, -1.0, 0.0}, 0);
  piston.make_piston(0.01, load_N);
  return NscdIntegrator(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston},
                        Eigen::Vector3d(0.0, -kG, 0.0), 3, parameters);
}

// The speed at the start of step k (1-based) of dropped_sphere(n), closed form (see above).
double start_speed(int k, int n) {
  if (k <= n) return (k - 1) * kStep * kG;
  if (k == n + 1) return n * kStep * kG / 2.0;
  return 0.0;
}


}  // namespace

// The trajectory the schedule's test relies on: speeds at the start of every step as derived
// above (to round-off), for a schedule that is off.
TEST(ToleranceSchedule, DroppedSphereSpeedsAreTheClosedFormOnes) {
  constexpr int n = 10;
  NscdIntegrator sim = dropped_sphere(n, {});
  for (int k = 1; k <= n + 4; ++k) {
    EXPECT_NEAR(sim.max_speed(), start_speed(k, n), 1e-12) << "start of step " << k;
    sim.step();
  }
  EXPECT_NEAR(sim.particles().position[0].y(), kRadius, 1e-12);
}

// The phase of every step, against the closed-form start speeds: falling from the first step
// that starts at or above fall_speed, landed (tight) from the first one after it that starts
// below; each step's report carries the tolerance it was solved at. Two thresholds: one the
// half-speed step n + 1 still exceeds (landing at n + 2), one it does not (landing at n + 1).
TEST(ToleranceSchedule, SwitchesWhereTheClosedFormSpeedsCrossFallSpeed) {
  constexpr int n = 10;
  for (const double units : {2.5, 5.5}) {  // fall_speed in units of h g (away from any speed)
    const double fall_speed = units * kStep * kG;
    const int first_fall = int(std::ceil(units)) + 1;           // start speed (k - 1) h g >= V
    const int landed = n * 0.5 >= units ? n + 2 : n + 1;        // first start below V after it
    NscdIntegrator sim = dropped_sphere(n, schedule(1e-9, 1e-3, fall_speed));
    for (int k = 1; k <= n + 5; ++k) {
      const bool falling = k >= first_fall && k < landed;
      const StepReport report = sim.step();
      EXPECT_EQ(report.fall, falling) << "fall_speed " << units << " h g, step " << k;
      EXPECT_EQ(report.tolerance, falling ? 1e-3 : 1e-9) << "step " << k;
      EXPECT_EQ(sim.tolerance_in_force(), report.tolerance);
      EXPECT_EQ(sim.tolerance_schedule().landed_step(), k >= landed ? landed : 0) << "step " << k;
    }
    EXPECT_EQ(sim.stats().fall_steps, landed - first_fall);
    EXPECT_EQ(sim.stats().fall_unconverged_steps, 0);
    EXPECT_EQ(sim.tolerance_schedule().phase(), ToleranceSchedule::Phase::Landed);
  }
}

// tighten_steps = 3 from 1e-3 to 1e-6: the landed steps take 1e-4, 1e-5 and then 1e-6 (a
// factor 10 per step), starting at the closed-form landing step.
TEST(ToleranceSchedule, TightensGeometricallyOverTightenSteps) {
  constexpr int n = 10;
  NscdParameters parameters = schedule(1e-6, 1e-3, 2.5 * kStep * kG);
  parameters.tighten_steps = 3;
  NscdIntegrator sim = dropped_sphere(n, parameters);
  const double expected[] = {1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3,
                             1e-3, 1e-4, 1e-5, 1e-6, 1e-6, 1e-6};  // steps 1-16, landing at 12
  for (int k = 1; k <= 16; ++k) {
    const StepReport report = sim.step();
    EXPECT_NEAR(report.tolerance, expected[k - 1], 1e-12 * expected[k - 1]) << "step " << k;
    EXPECT_EQ(report.fall, k >= 4 && k < 12) << "step " << k;
  }
  EXPECT_EQ(sim.tolerance_schedule().landed_step(), n + 2);
  EXPECT_EQ(sim.stats().fall_steps, 8);
  EXPECT_THROW(ToleranceSchedule(1e-6, 1e-3, 0.1, 0), std::invalid_argument);
}

// A new load on a landed bed (NscdIntegrator::set_piston_load) starts the ramp again, as a
// landing does: a piston falls onto a sphere resting on the floor and lands; given four times
// its load, the next steps are solved from fall_tolerance down to tolerance again (1e-3 to 1e-9
// over 3 steps: 1e-5, 1e-7, 1e-9). The same load set again changes nothing.
TEST(ToleranceSchedule, ANewPistonLoadStartsTheRampAgain) {
  NscdParameters parameters = schedule(1e-9, 1e-3, 0.05);
  parameters.tighten_steps = 3;
  NscdIntegrator sim = piston_over_sphere(1.0, parameters);
  for (int k = 0; k < 200 && sim.tolerance_schedule().landed_step() == 0; ++k) sim.step();
  const std::int64_t landed = sim.tolerance_schedule().landed_step();
  ASSERT_GT(landed, 1);
  for (int k = 0; k < 5; ++k) sim.step();
  EXPECT_EQ(sim.step().tolerance, 1e-9);
  sim.set_piston_load(1, 1.0);  // the load it has
  EXPECT_EQ(sim.step().tolerance, 1e-9);
  EXPECT_EQ(sim.tolerance_schedule().landed_step(), landed);
  sim.set_piston_load(1, 4.0);
  const std::int64_t again = sim.stats().steps + 1;
  for (const double expected : {1e-5, 1e-7, 1e-9, 1e-9}) {
    const StepReport report = sim.step();
    EXPECT_NEAR(report.tolerance, expected, 1e-12 * expected) << "step " << sim.stats().steps;
    EXPECT_FALSE(report.fall);
  }
  EXPECT_EQ(sim.tolerance_schedule().landed_step(), again);
  // Before any fall, and with tighten_steps 1, a new load changes nothing.
  ToleranceSchedule before(1e-9, 1e-3, 0.05, 3);
  before.ramp_again_from(1);
  EXPECT_EQ(before.tolerance_for_step(0.0, 0.0, 1), 1e-9);
  ToleranceSchedule at_once(1e-9, 1e-3, 0.05, 1);
  EXPECT_EQ(at_once.tolerance_for_step(1.0, 1.0, 1), 1e-3);
  EXPECT_EQ(at_once.tolerance_for_step(0.0, 0.0, 2), 1e-9);
  at_once.ramp_again_from(3);
  EXPECT_EQ(at_once.tolerance_for_step(0.0, 0.0, 3), 1e-9);
  EXPECT_EQ(at_once.landed_step(), 2);
}

// A piston compacting the bed keeps the schedule falling from any phase, and the fall ends
// only once no piston compacts either. The schedule alone, speeds given: fall_speed 0.05 m/s,
// 1e-3 to 1e-9 over 3 steps.
TEST(ToleranceSchedule, ACompactingPistonKeepsTheFallTolerance) {
  ToleranceSchedule s(1e-9, 1e-3, 0.05, 3);
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.0, 1, false), 1e-9);  // at rest: before, tight
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.0, 2, true), 1e-3);   // compacting: falling
  EXPECT_TRUE(s.falling());
  // Every particle below fall_speed, the piston still compacting: still falling.
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.01, 3, true), 1e-3);
  // A particle still falling, the piston no longer compacting: still falling (the fall's rule).
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.06, 4, false), 1e-3);
  // Neither: landed at step 5, the ramp 1e-5, 1e-7, 1e-9.
  for (const auto& [step, expected] : {std::pair{5, 1e-5}, std::pair{6, 1e-7}, std::pair{7, 1e-9}})
    EXPECT_NEAR(s.tolerance_for_step(0.0, 0.01, step, false), expected, 1e-12 * expected) << step;
  EXPECT_EQ(s.landed_step(), 5);
  // The load makes the landed bed flow again: falling, and a new ramp when it stops.
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.01, 8, true), 1e-3);
  EXPECT_EQ(s.phase(), ToleranceSchedule::Phase::Falling);
  EXPECT_NEAR(s.tolerance_for_step(0.0, 0.01, 9, false), 1e-5, 1e-17);
  EXPECT_EQ(s.landed_step(), 9);
  // With the schedule off a compacting piston changes nothing.
  ToleranceSchedule off(1e-9, 0.0, 0.05, 3);
  EXPECT_EQ(off.tolerance_for_step(0.0, 0.0, 1, true), 1e-9);
}

// Through the integrator (NscdIntegrator::piston_compacting): a 10 g piston released half a
// radius above a sphere resting on the floor, fall_speed too high for anything to fall (10 m/s).
// With compaction_speed 1e-4 m/s the steps while the piston moves are falling steps, solved at
// fall_tolerance; once it rests on the sphere the tolerance ramps back (3 steps) and stays
// tight. With compaction_speed 0 every step is tight. The automatic compaction speed is
// compaction_fraction h |F / m + g.n|, and follows a new load. nncg, which stops on Siconos'
// residual; with nlgs (the change per sweep) there is no compaction speed. Tolerances 1e-7 and
// 1e-10: at a fall tolerance of 1e-3 the 10 g piston on the 33 mg sphere (nlgs) rocked at up to
// 6 mm/s for 50 steps after landing, above its compaction speed all along.
TEST(ToleranceSchedule, AFallingPistonIsSolvedAtTheFallTolerance) {
  const auto make = [](std::optional<double> compaction_speed, const char* solver = "nncg") {
    NscdParameters parameters = schedule(1e-10, 1e-7, 10.0);
    parameters.tighten_steps = 3;
    parameters.compaction_speed = compaction_speed;
    parameters.solver = solver;  // nncg stops on Siconos' residual
    return piston_over_sphere(0.0, parameters);
  };
  NscdIntegrator sim = make(1e-4);
  int falling_steps = 0;
  for (int k = 1; k <= 60; ++k) {
    const bool moving = std::abs(sim.walls()[1].velocity_m_per_s) >= 1e-4;
    const StepReport report = sim.step();
    EXPECT_EQ(report.fall, moving) << "step " << k;
    if (moving) {
      EXPECT_EQ(report.tolerance, 1e-7) << "step " << k;
      ++falling_steps;
    }
  }
  EXPECT_GT(falling_steps, 3);                       // it fell half a radius
  EXPECT_LT(std::abs(sim.walls()[1].velocity_m_per_s), 1e-4);  // and rests on the sphere
  EXPECT_GT(sim.tolerance_schedule().landed_step(), falling_steps);
  EXPECT_EQ(sim.step().tolerance, 1e-10);            // the ramp is over
  EXPECT_EQ(sim.stats().fall_steps, falling_steps);
  NscdIntegrator off = make(0.0);
  for (int k = 1; k <= 60; ++k) {
    const StepReport report = off.step();
    EXPECT_FALSE(report.fall);
    EXPECT_EQ(report.tolerance, 1e-10);
  }
  NscdParameters bad = schedule(1e-9, 1e-3, 0.1);
  bad.compaction_speed = -1.0;
  EXPECT_THROW(dropped_sphere(3, bad), std::invalid_argument);
  bad.compaction_speed = std::nullopt;
  bad.compaction_fraction = -0.01;
  EXPECT_THROW(dropped_sphere(3, bad), std::invalid_argument);
  // Automatic: a hundredth of h |F / m + g.n| = 1e-3 s x (0 + 9.81) m/s^2, then with 1 N on 10 g
  // 1e-3 x (100 + 9.81); the floor, a fixed wall, has none.
  NscdIntegrator automatic = make(std::nullopt);
  EXPECT_DOUBLE_EQ(automatic.compaction_speed_m_per_s(1, kStep), 0.01 * kStep * kG);
  automatic.set_piston_load(1, 1.0);
  EXPECT_DOUBLE_EQ(automatic.compaction_speed_m_per_s(1, kStep), 0.01 * kStep * (100.0 + kG));
  EXPECT_EQ(automatic.compaction_speed_m_per_s(0, kStep), 0.0);
  // A solver that stops on the change per sweep has none: its bed creeps by itself.
  EXPECT_EQ(make(1e-4, "nlgs").compaction_speed_m_per_s(1, kStep), 0.0);
  NscdIntegrator sweeps = make(1e-4, "nlgs");
  for (int k = 1; k <= 20; ++k) EXPECT_FALSE(sweeps.step().fall) << "step " << k;
}

// One-way for the particles: after landing, speeds above fall_speed again (the sphere kicked
// upwards) keep the tight tolerance (only a compacting piston makes a landed bed fall again).
TEST(ToleranceSchedule, LandedStaysLanded) {
  constexpr int n = 10;
  NscdIntegrator sim = dropped_sphere(n, schedule(1e-9, 1e-3, 2.5 * kStep * kG));
  for (int k = 1; k <= n + 2; ++k) sim.step();
  ASSERT_EQ(sim.tolerance_schedule().landed_step(), n + 2);
  sim.particles().velocity[0] = Eigen::Vector3d(0.0, 1.0, 0.0);  // 1 m/s up: far above 2.5 h g
  for (int k = 0; k < 5; ++k) {
    const StepReport report = sim.step();
    EXPECT_FALSE(report.fall);
    EXPECT_EQ(report.tolerance, 1e-9);
  }
  EXPECT_EQ(sim.tolerance_schedule().landed_step(), n + 2);
}

// The fall is judged on the speed fall_share of the moving particles reach (at least one), not
// on the fastest: 200 spheres resting apart on a floor, `fast` of them thrown up at 1 m/s (far
// above fall_speed, 0.1 m/s). With fall_share 0.01 two fast spheres are the 1% that makes a
// fall and one is not; with fall_share 0 one is enough (the fastest alone). The fall ends only
// when the fastest has landed.
TEST(ToleranceSchedule, FallIsJudgedOnTheShareOfParticlesAtFallSpeed) {
  const auto make = [](int fast, double share) {
    NscdParameters p = schedule(1e-9, 1e-3, 0.1);
    p.time_step = kStep;
    p.fall_share = share;
    ParticleSet set;
    for (int i = 0; i < 200; ++i)
      set.add(Eigen::Vector3d(3.0 * kRadius * i, kRadius, 0.0), kRadius, sphere_mass(kRadius, kDensity), 0);
    for (int i = 0; i < fast; ++i) set.velocity[std::size_t(37 * i + 5)] = Eigen::Vector3d(0.0, 1.0, 0.0);
    return NscdIntegrator(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                          Eigen::Vector3d(0, -kG, 0), 3, p);
  };
  const auto first_step = [&](int fast, double share) { return make(fast, share).step(); };
  for (const auto& [fast, share, falls] :
       {std::tuple{0, 0.01, false}, std::tuple{1, 0.01, false}, std::tuple{2, 0.01, true},
        std::tuple{5, 0.01, true}, std::tuple{1, 0.0, true}, std::tuple{2, 0.02, false},
        std::tuple{4, 0.02, true}}) {
    const StepReport report = first_step(fast, share);
    EXPECT_EQ(report.fall, falls) << fast << " fast, fall_share " << share;
    EXPECT_EQ(report.tolerance, falls ? 1e-3 : 1e-9) << fast << " fast, fall_share " << share;
  }
  // A fall ends when the fastest particle has landed, not when the share has: one sphere still
  // at 1 m/s keeps the fall tolerance, and the step after it stops is tight.
  NscdIntegrator sim = make(5, 0.01);
  EXPECT_TRUE(sim.step().fall);
  for (auto& v : sim.particles().velocity) v.setZero();
  sim.particles().velocity[5] = Eigen::Vector3d(0.0, 1.0, 0.0);
  EXPECT_TRUE(sim.step().fall);
  for (auto& v : sim.particles().velocity) v.setZero();
  const StepReport landed = sim.step();
  EXPECT_FALSE(landed.fall);
  EXPECT_EQ(landed.tolerance, 1e-9);
  EXPECT_EQ(sim.tolerance_schedule().phase(), ToleranceSchedule::Phase::Landed);
  NscdParameters bad = schedule(1e-9, 1e-3, 0.1);
  bad.fall_share = 1.5;
  EXPECT_THROW(dropped_sphere(3, bad), std::invalid_argument);
}

// Particles that never reach fall_speed are solved at `tolerance` throughout.
TEST(ToleranceSchedule, NeverFastEnoughMeansTightThroughout) {
  NscdIntegrator sim = dropped_sphere(10, schedule(1e-9, 1e-3, 1.0));  // 1 m/s: never reached
  for (int k = 0; k < 20; ++k) {
    const StepReport report = sim.step();
    EXPECT_FALSE(report.fall);
    EXPECT_EQ(report.tolerance, 1e-9);
  }
  EXPECT_EQ(sim.stats().fall_steps, 0);
  EXPECT_EQ(sim.tolerance_schedule().phase(), ToleranceSchedule::Phase::Before);
}

// The tolerance in force is the one the solver stops at: on a pouring 3D pile, a falling step
// stops as soon as its residual is below fall_tolerance (so some stop above the tight tolerance,
// having used fewer sweeps), a landed step only below tolerance; converged means below the
// tolerance of its own step.
TEST(ToleranceSchedule, TheSolverStopsAtTheToleranceInForce) {
  constexpr double tight = 1e-8, loose = 1e-3;
  NscdParameters parameters = schedule(tight, loose, 0.05);
  parameters.max_iterations = 20000;
  NscdIntegrator sim = random_pile(40, 3, 0.3, 7, parameters);
  int falling_above_tight = 0, landed_solved = 0;
  for (int k = 0; k < 400; ++k) {
    const StepReport report = sim.step();
    const bool landed = sim.tolerance_schedule().phase() == ToleranceSchedule::Phase::Landed;
    ASSERT_EQ(report.tolerance, report.fall ? loose : tight);
    if (report.converged && report.candidates > 0 && report.sweeps > 0) {
      EXPECT_LE(report.residual, report.tolerance) << "step " << k + 1;
      if (report.fall && report.residual > tight) ++falling_above_tight;
      if (landed && report.active_contacts > 0) ++landed_solved;
    }
  }
  ASSERT_GT(sim.tolerance_schedule().landed_step(), 0) << "the pile should land within 400 steps";
  EXPECT_GT(sim.stats().fall_steps, 10);
  EXPECT_GT(falling_above_tight, 0) << "no falling step stopped at the loose tolerance";
  EXPECT_GT(landed_solved, 0);
}

// A restored integrator continues bit for bit across the switch: saved while falling, both
// tighten at the same step and take the same steps after it (and through a 4-step ramp).
TEST(ToleranceSchedule, RestoredIntegratorContinuesBitwiseAcrossTheSwitch) {
  for (const char* solver : {"nlgs", "nncg", "apgd", "nncg ramp"}) {
    NscdParameters parameters = schedule(1e-7, 1e-3, 0.05);
    parameters.solver = std::string(solver) == "nncg ramp" ? "nncg" : solver;
    if (std::string(solver) == "nncg ramp") parameters.tighten_steps = 4;  // saved before it
    NscdIntegrator probe = random_pile(40, 3, 0.3, 7, parameters);
    for (int k = 0; k < 400 && probe.tolerance_schedule().landed_step() == 0; ++k) probe.step();
    const std::int64_t landed = probe.tolerance_schedule().landed_step();
    ASSERT_GT(landed, 20) << solver;

    NscdIntegrator original = random_pile(40, 3, 0.3, 7, parameters);
    const int before = int(landed) - 10;  // falling
    for (int k = 0; k < before; ++k) original.step();
    ASSERT_TRUE(original.tolerance_schedule().falling()) << solver;
    const MechanicsState saved = original.save_state();
    EXPECT_EQ(saved.tolerance_schedule.phase, ToleranceSchedule::Phase::Falling);
    NscdIntegrator restored = random_pile(40, 3, 0.3, 7, parameters);
    restored.restore_state(saved);
    for (int k = 0; k < 40; ++k) {
      const StepReport a = original.step(), b = restored.step();
      ASSERT_EQ(a.tolerance, b.tolerance) << solver << ", step " << before + k + 1;
      ASSERT_EQ(a.sweeps, b.sweeps) << solver << ", step " << before + k + 1;
      ASSERT_TRUE(same_bits(original.particles().position, restored.particles().position))
          << solver << ", step " << before + k + 1;
      ASSERT_TRUE(same_bits(original.particles().velocity, restored.particles().velocity));
      ASSERT_TRUE(same_bits(original.particles().angular_velocity,
                                restored.particles().angular_velocity));
    }
    EXPECT_EQ(original.tolerance_schedule().landed_step(), landed) << solver;
    EXPECT_EQ(restored.tolerance_schedule().landed_step(), landed) << solver;
    EXPECT_EQ(restored.stats().fall_steps, original.stats().fall_steps);
    EXPECT_EQ(restored.stats().unconverged_steps, original.stats().unconverged_steps);

    // The phase is what makes it so: saved after landing and restored without it (Before), a
    // restarted run whose particles are fast again would go back to the loose tolerance.
    MechanicsState landed_state = original.save_state();
    ASSERT_EQ(landed_state.tolerance_schedule.phase, ToleranceSchedule::Phase::Landed);
    NscdIntegrator kept = random_pile(40, 3, 0.3, 7, parameters);
    kept.restore_state(landed_state);
    EXPECT_EQ(kept.tolerance_schedule().landed_step(), landed);
    landed_state.tolerance_schedule = {};
    NscdIntegrator forgetful = random_pile(40, 3, 0.3, 7, parameters);
    forgetful.restore_state(landed_state);
    for (auto* sim : {&kept, &forgetful}) sim->particles().velocity[0] = Eigen::Vector3d(0, 1, 0);
    EXPECT_EQ(kept.step().tolerance, 1e-7) << solver;
    EXPECT_EQ(forgetful.step().tolerance, 1e-3) << solver << ": the saved phase should matter";
  }
}

// A fall_tolerance equal to tolerance gives the bits of no schedule at all (docs/mechanics.md's way
// to measure an example's earlier settings again), while a looser one does not.
TEST(ToleranceSchedule, EqualTolerancesGiveTheBitsOfNoSchedule) {
  NscdParameters none = nlgs_parameters();
  none.tolerance = 1e-4;
  NscdIntegrator plain = random_pile(40, 3, 0.3, 7, none);
  NscdIntegrator same = random_pile(40, 3, 0.3, 7, schedule(1e-4, 1e-4, 0.05));
  NscdIntegrator looser = random_pile(40, 3, 0.3, 7, schedule(1e-4, 1e-2, 0.05));
  bool looser_differs = false;
  for (int k = 0; k < 200; ++k) {
    plain.step();
    const StepReport report = same.step();
    looser.step();
    ASSERT_TRUE(same_bits(plain.particles().position, same.particles().position)) << k;
    ASSERT_TRUE(same_bits(plain.particles().velocity, same.particles().velocity)) << k;
    EXPECT_EQ(report.tolerance, 1e-4);
    looser_differs = looser_differs || !same_bits(plain.particles().velocity, looser.particles().velocity);
  }
  EXPECT_GT(same.stats().fall_steps, 0);  // it did fall: the schedule ran, at one tolerance
  EXPECT_TRUE(looser_differs);
}

TEST(ToleranceSchedule, BadValuesAreRefused) {
  EXPECT_THROW(ToleranceSchedule(1e-6, 1e-4, 0.0), std::invalid_argument);
  EXPECT_THROW(ToleranceSchedule(1e-6, 1e-4, -1.0), std::invalid_argument);
  EXPECT_THROW(ToleranceSchedule(1e-6, 1e-4, std::nan("")), std::invalid_argument);
  EXPECT_THROW(ToleranceSchedule(1e-6, std::nan(""), 0.1), std::invalid_argument);
  EXPECT_THROW(ToleranceSchedule(1e-6, -1e-4, 0.1), std::invalid_argument);
  EXPECT_NO_THROW(ToleranceSchedule(1e-6, 0.0, 0.0));  // off
  EXPECT_THROW(dropped_sphere(10, schedule(1e-6, -1e-4, 0.1)), std::invalid_argument);
  EXPECT_THROW(dropped_sphere(10, schedule(1e-6, 1e-4, -0.1)), std::invalid_argument);
  EXPECT_NO_THROW(dropped_sphere(10, schedule(1e-6, 1e-4, 0.0)));  // automatic
}

// fall_speed 0 is automatic: fall_travel_fraction of the smallest radius per time step. A fall
// tolerance tighter than the tolerance is raised to it (the fall never the hardest part).
TEST(ToleranceSchedule, AutomaticFallSpeedAndNeverTighterThanTolerance) {
  NscdParameters parameters = schedule(1e-6, 1e-3, 0.0);
  parameters.fall_travel_fraction = 0.25;
  const NscdIntegrator sim = dropped_sphere(10, parameters);
  EXPECT_DOUBLE_EQ(sim.tolerance_schedule().fall_speed_m_per_s(), 0.25 * kRadius / kStep);
  EXPECT_EQ(sim.tolerance_schedule().fall_tolerance(), 1e-3);
  EXPECT_EQ(ToleranceSchedule(1e-4, 1e-6, 0.1).fall_tolerance(), 1e-4);
  EXPECT_EQ(ToleranceSchedule(1e-4, 1e-6, 0.1).tolerance_for_step(1.0, 1.0, 1), 1e-4);  // falling
}

// A collapse (ToleranceSchedule::begin_collapse) begins only outside a fall, with the schedule
// on and looser than `tolerance`, at a tenth of fall_speed or faster; it is solved at
// fall_tolerance while the fastest particle moves at that tenth or faster (below fall_speed, where
// a fall would have ended), then landed and tight.
TEST(ToleranceSchedule, ACollapseBeginsOnlyOutsideAFallAtATenthOfFallSpeed) {
  ToleranceSchedule s(1e-9, 1e-3, 0.1, 1);
  EXPECT_DOUBLE_EQ(s.collapse_speed_m_per_s(), 0.01);
  EXPECT_FALSE(s.begin_collapse(0.009));
  EXPECT_EQ(s.phase(), ToleranceSchedule::Phase::Before);
  EXPECT_TRUE(s.begin_collapse(0.011));
  EXPECT_EQ(s.phase(), ToleranceSchedule::Phase::Collapsing);
  EXPECT_TRUE(s.falling());
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.05, 1), 1e-3);
  EXPECT_EQ(s.phase(), ToleranceSchedule::Phase::Collapsing);
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.005, 2), 1e-9);
  EXPECT_EQ(s.phase(), ToleranceSchedule::Phase::Landed);
  EXPECT_EQ(s.landed_step(), 2);
  // Landed, a bed may collapse again.
  EXPECT_TRUE(s.begin_collapse(0.02));
  EXPECT_EQ(s.tolerance_for_step(0.0, 0.02, 3), 1e-3);

  ToleranceSchedule falling(1e-9, 1e-3, 0.1, 1);
  ASSERT_EQ(falling.tolerance_for_step(0.2, 0.2, 1), 1e-3);
  EXPECT_FALSE(falling.begin_collapse(1.0));
  EXPECT_EQ(falling.phase(), ToleranceSchedule::Phase::Falling);
  EXPECT_FALSE(ToleranceSchedule(1e-9, 0.0, 0.1).begin_collapse(1.0));  // no schedule
  EXPECT_FALSE(ToleranceSchedule(1e-3, 1e-3, 0.1).begin_collapse(1.0));  // nothing looser to go to
}
