// NSCD against exact answers: resting sphere, column, incline (rolling / slipping),
// inelastic impact, fixed particles, friction between two materials, reporting.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

NscdIntegrator single_sphere(const Vector3d& position, const std::vector<Wall>& walls,
                             double friction, NscdParameters parameters = nlgs_parameters(),
                             std::vector<Material> materials = {}) {
  ParticleSet set;
  set.add(position, kRadius, sphere_mass(kRadius, kDensity), 0);
  if (materials.empty()) materials = {steel(friction)};
  return NscdIntegrator(std::move(set), std::move(materials), walls, Vector3d(0, -kG, 0), 3,
                        parameters);
}

}  // namespace

TEST(NscdExact, SphereRestingOnPlaneCarriesItsWeight) {
  auto sim = single_sphere(Vector3d(0, kRadius, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)}, 0.3);
  const double weight = sphere_mass(kRadius, kDensity) * kG;
  for (int step = 0; step < 10000; ++step) {
    const StepReport report = sim.step();
    ASSERT_TRUE(report.converged);
    ASSERT_EQ(sim.contacts().size(), 1u) << "step " << step;
    ASSERT_NEAR(sim.contacts()[0].normal_force_N, weight, 1e-6 * weight) << "step " << step;
  }
  const ContactForce& c = sim.contacts()[0];
  EXPECT_EQ(c.i, 0);
  EXPECT_EQ(c.j, -1);
  EXPECT_EQ(c.normal, Vector3d(0, 1, 0));
  EXPECT_NEAR(c.normal_impulse_Ns, weight * 1e-3, 1e-6 * weight * 1e-3);
  EXPECT_LT(c.tangential_force_N.norm(), 1e-12 * weight);
  EXPECT_LT(sim.stats().max_penetration_m, 1e-9 * kRadius);
  EXPECT_NEAR(sim.particles().position[0].y(), kRadius, 1e-9 * kRadius);
  EXPECT_EQ(sim.stats().steps, 10000);
  EXPECT_EQ(sim.stats().unconverged_steps, 0);
}

TEST(NscdExact, ColumnContactsCarryTheWeightAbove) {
  const int count = 10;
  ParticleSet set;
  for (int k = 0; k < count; ++k) {
    set.add(Vector3d(0, kRadius * (2 * k + 1), 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  }
  // The stop test bounds the change of one sweep, not the error: along a chain Gauss-Seidel
  // contracts slowly (rate ~ cos^2(pi / (2N + 1))) and the error is ~50x the last change for
  // N = 10. A tolerance of 1e-9 gives forces to 1e-6 (at 1e-6 they are within ~5e-5).
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-9;
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, parameters);
  for (int step = 0; step < 200; ++step) sim.step();
  const double weight = sphere_mass(kRadius, kDensity) * kG;
  ASSERT_EQ(sim.contacts().size(), static_cast<std::size_t>(count));
  for (const ContactForce& c : sim.contacts()) {
    // The contact under sphere k is (k - 1, k), or the floor for k = 0.
    const std::int64_t k = c.j < 0 ? 0 : c.j;
    if (c.j >= 0) {
      EXPECT_EQ(c.i, k - 1);
    } else {
      EXPECT_EQ(c.i, 0);
    }
    const double expected = weight * static_cast<double>(count - k);
    EXPECT_NEAR(c.normal_force_N, expected, 1e-6 * expected) << "under sphere " << k;
    // Normal from j to i: up from the floor, down from the sphere above (i < j is lower).
    EXPECT_EQ(c.normal, Vector3d(0, c.j < 0 ? 1.0 : -1.0, 0));
  }
  EXPECT_LT(sim.stats().max_penetration_m, 1e-9 * kRadius);
  EXPECT_EQ(sim.stats().unconverged_steps, 0);
}

namespace {

// Sphere released at rest on a 30-degree incline through the origin; returns the speed
// along the slope after `duration` and the spin rate times R.
struct InclineResult {
  double speed;       // m/s, down the slope
  double rolling;     // omega R, m/s (equals speed when rolling without slip)
  double off_slope;   // |v . n|, m/s
};

InclineResult run_incline(double particle_friction, double wall_friction, double duration,
                          double h = 1e-3) {
  const double angle = std::numbers::pi / 6.0;
  const Vector3d n(-std::sin(angle), std::cos(angle), 0.0);
  const Vector3d down(-std::cos(angle), -std::sin(angle), 0.0);
  ParticleSet set;
  set.add(kRadius * n, kRadius, sphere_mass(kRadius, kDensity), 0);
  NscdParameters parameters = nlgs_parameters();
  parameters.time_step = h;
  NscdIntegrator sim(std::move(set), {steel(particle_friction), steel(wall_friction)},
                     {Wall::through({0, 0, 0}, n, 1)}, Vector3d(0, -kG, 0), 3, parameters);
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int s = 0; s < steps; ++s) sim.step();
  const auto& p = sim.particles();
  return {p.velocity[0].dot(down), p.angular_velocity[0].norm() * kRadius,
          std::abs(p.velocity[0].dot(n))};
}

}  // namespace

TEST(NscdExact, SphereRollsWithoutSlipOnRoughIncline) {
  const double t = 0.5;
  const auto result = run_incline(0.5, 0.5, t);
  const double expected = 5.0 / 7.0 * kG * 0.5 * t;  // a = 5/7 g sin(30 deg)
  EXPECT_NEAR(result.speed, expected, 0.01 * expected);
  EXPECT_NEAR(result.rolling, result.speed, 1e-6 * expected);  // no slip at the contact
  EXPECT_LT(result.off_slope, 1e-9);
}

TEST(NscdExact, SphereSlipsOnSmoothIncline) {
  const double t = 0.5, mu = 0.1;
  const auto result = run_incline(mu, mu, t);
  const double cos30 = std::sqrt(3.0) / 2.0;
  const double expected = kG * (0.5 - mu * cos30) * t;
  EXPECT_NEAR(result.speed, expected, 0.01 * expected);
  // Friction torque spins it up: omega R = (5/2) mu g cos(theta) t, slower than the slide.
  EXPECT_NEAR(result.rolling, 2.5 * mu * kG * cos30 * t, 0.01 * result.rolling);
  EXPECT_LT(result.rolling, result.speed);
}

TEST(NscdExact, FrictionBetweenMaterialsIsTheSmallerCoefficient) {
  // Rough sphere on a smooth wall: slips as with mu = 0.1.
  const double t = 0.5, mu = 0.1;
  const auto result = run_incline(0.9, mu, t);
  const double expected = kG * (0.5 - mu * std::sqrt(3.0) / 2.0) * t;
  EXPECT_NEAR(result.speed, expected, 0.01 * expected);
}

TEST(NscdExact, ImpactOnPlaneIsInelastic) {
  // Dropped from 5 mm above the floor; 3D, with a slight sideways velocity.
  const double drop = 5e-3;
  auto sim = single_sphere(Vector3d(0, kRadius + drop, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                           0.3);
  sim.particles().velocity[0] = Vector3d(0.01, 0, 0);
  const double impact_speed = std::sqrt(2 * kG * drop);
  int first_contact = -1;
  double max_height_after = 0.0;
  for (int step = 0; step < 300; ++step) {
    sim.step();
    const auto& p = sim.particles();
    if (first_contact < 0 && !sim.contacts().empty()) {
      first_contact = step;
      // The step that catches the sphere slows it down without reversing it.
      EXPECT_LE(p.velocity[0].y(), 0.0);
    } else if (first_contact >= 0) {
      // From the next step on, the normal velocity is zero: no bounce.
      EXPECT_NEAR(p.velocity[0].y(), 0.0, 1e-12 * impact_speed) << "step " << step;
      max_height_after = std::max(max_height_after, p.position[0].y());
    }
  }
  ASSERT_GT(first_contact, 0);
  EXPECT_LE(max_height_after, kRadius * (1 + 1e-12));
  EXPECT_LT(sim.stats().max_penetration_m, 1e-9 * kRadius);
}

TEST(NscdExact, FixedParticleNeverMovesAndHoldsTheOtherOne) {
  ParticleSet set;
  const double m = sphere_mass(kRadius, kDensity);
  set.add(Vector3d(0, 0, 0), kRadius, m, 0, /*fixed=*/true);
  set.add(Vector3d(0, 2 * kRadius, 0), kRadius, m, 0);
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {}, Vector3d(0, -kG, 0), 3);
  for (int step = 0; step < 1000; ++step) sim.step();
  EXPECT_EQ(sim.particles().position[0], Vector3d(0, 0, 0));
  EXPECT_EQ(sim.particles().velocity[0], Vector3d(0, 0, 0));
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_NEAR(sim.contacts()[0].normal_force_N, m * kG, 1e-9 * m * kG);
  EXPECT_EQ(sim.contacts()[0].normal, Vector3d(0, -1, 0));  // from j = 1 to i = 0
  // Energies count moving particles only.
  EXPECT_NEAR(sim.potential_energy(), m * kG * 2 * kRadius, 1e-12 * m * kG * kRadius);
}

TEST(NscdExact, UnconvergedStepsAreCounted) {
  NscdParameters parameters = nlgs_parameters();
  parameters.max_iterations = 1;
  parameters.tolerance = 1e-12;
  // From zero impulses: the static warm start is this column's exact statics, which one sweep
  // confirms (test_static_warm_start.cpp).
  parameters.static_warm_start = false;
  ParticleSet set;
  for (int k = 0; k < 5; ++k) {
    set.add(Vector3d(0, kRadius * (2 * k + 1), 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  }
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, parameters);
  const StepReport first = sim.step();
  EXPECT_FALSE(first.converged);
  EXPECT_EQ(first.sweeps, 1);
  EXPECT_GT(first.residual, 1e-12);
  EXPECT_EQ(sim.stats().unconverged_steps, 1);
  EXPECT_EQ(sim.stats().max_sweeps, 1);
}

TEST(NscdExact, RejectsInconsistentInput) {
  ParticleSet set;
  set.add(Vector3d(0, 1, 0), kRadius, 1.0, 3);  // material 3 does not exist
  EXPECT_THROW(NscdIntegrator(set, {steel(0.3)}, {}, Vector3d(0, -kG, 0), 3), std::invalid_argument);
  set.material[0] = 0;
  EXPECT_THROW(NscdIntegrator(set, {steel(0.3)}, {}, Vector3d(0, -kG, 0), 4), std::invalid_argument);
  NscdParameters bad = nlgs_parameters();
  bad.theta = 0.0;
  EXPECT_THROW(NscdIntegrator(set, {steel(0.3)}, {}, Vector3d(0, -kG, 0), 3, bad),
               std::invalid_argument);
  set.radius[0] = -1.0;
  EXPECT_THROW(NscdIntegrator(set, {steel(0.3)}, {}, Vector3d(0, -kG, 0), 3), std::invalid_argument);
}

namespace {

// A sphere of radius R flying at 2 m/s (no gravity) with a step that moves it 1.5 R per step,
// towards `target` (a wall, or a fixed sphere); returns the smallest gap seen, m.
double smallest_gap_of_fast_sphere(bool towards_sphere) {
  const double speed = 2.0, h = 1.5 * kRadius / speed;
  ParticleSet set;
  const double m = sphere_mass(kRadius, kDensity);
  set.add(Vector3d(20.3 * kRadius, 0, 0), kRadius, m, 0);
  std::vector<Wall> walls;
  if (towards_sphere) {
    set.add(Vector3d(0, 0, 0), kRadius, m, 0, /*fixed=*/true);
  } else {
    walls.push_back(Wall::through({0, 0, 0}, {1, 0, 0}, 0));
  }
  set.velocity[0] = Vector3d(-speed, 0, 0);
  NscdParameters parameters = nlgs_parameters();
  parameters.time_step = h;
  NscdIntegrator sim(std::move(set), {steel(0.3)}, walls, Vector3d::Zero(), 3, parameters);
  double smallest = 1.0;
  for (int step = 0; step < 60; ++step) {
    sim.step();
    const double x = sim.particles().position[0].x();
    smallest = std::min(smallest, towards_sphere ? x - 2 * kRadius : x - kRadius);
  }
  return smallest;
}

}  // namespace

TEST(NscdExact, FastSphereNeverPassesAWall) {
  EXPECT_GE(smallest_gap_of_fast_sphere(false), -1e-9 * kRadius);
}

TEST(NscdExact, FastSphereNeverPassesAnotherSphere) {
  EXPECT_GE(smallest_gap_of_fast_sphere(true), -1e-9 * kRadius);
}

// Penetration slop and split-impulse correction (PenetrationCorrection.h): an overlap d
// within the slop is held (no push-out, the sphere stays at rest exactly); beyond it the
// position step removes d - slop by moving the centre, and the velocity stays exactly zero.
TEST(NscdExact, PenetrationWithinTheSlopIsHeldNotPushedOut) {
  NscdParameters parameters = nlgs_parameters();  // slop 1e-4 r
  const double slop = parameters.penetration_slop_fraction * kRadius;
  const double d = 0.5 * slop;
  auto sim = single_sphere(Vector3d(0, kRadius - d, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                           0.3, parameters);
  for (int step = 0; step < 1000; ++step) {
    const StepReport report = sim.step();
    ASSERT_LT(sim.max_speed(), 1e-15) << "step " << step;
    ASSERT_NEAR(sim.particles().position[0].y(), kRadius - d, 1e-15) << "step " << step;
    ASSERT_EQ(report.correction_sweeps, 0) << "step " << step;
  }
  // Without a slop the same overlap is removed by the position step within one step, and
  // still no speed is made of it (the old push-out left the sphere moving at d / h).
  parameters.penetration_slop_fraction = 0.0;
  auto pushed = single_sphere(Vector3d(0, kRadius - d, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                              0.3, parameters);
  pushed.step();
  EXPECT_LT(pushed.max_speed(), 1e-15);
  EXPECT_NEAR(pushed.particles().position[0].y(), kRadius, 1e-15);
}

TEST(NscdExact, PenetrationBeyondTheSlopIsRemovedWithoutSpeed) {
  NscdParameters parameters = nlgs_parameters();
  const double slop = parameters.penetration_slop_fraction * kRadius;
  const double h = parameters.time_step;
  const double d = 5.0 * slop;
  auto sim = single_sphere(Vector3d(0, kRadius - d, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                           0.3, parameters);
  const StepReport first = sim.step();
  EXPECT_GT(first.correction_sweeps, 0);
  // Velocity step: U_n = u_n >= 0 (no bias for an overlap), so gravity is simply stopped.
  EXPECT_LT(sim.max_speed(), 1e-15);
  // Position step: the centre moves up by d - slop, the overlap is exactly the slop.
  EXPECT_NEAR(sim.particles().position[0].y(), kRadius - slop, 1e-15);
  for (int step = 0; step < 100; ++step) {
    sim.step();
    ASSERT_LT(sim.max_speed(), 1e-15) << "step " << step;
    ASSERT_NEAR(sim.particles().position[0].y(), kRadius - slop, 1e-15) << "step " << step;
  }
  // A recovery speed caps the correction per step at h * recovery_speed (still no speed).
  parameters.recovery_speed = 0.1 * (d - slop) / h;
  auto capped = single_sphere(Vector3d(0, kRadius - d, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                              0.3, parameters);
  capped.step();
  EXPECT_LT(capped.max_speed(), 1e-15);
  EXPECT_NEAR(capped.particles().position[0].y(), kRadius - d + 0.1 * (d - slop), 1e-15);
  // 0.4 slop per step: 5, 4.6, ..., 2.2, 1.8 slops deep after 8 steps; then within twice the
  // slop (PenetrationCorrection::kTrigger), where an overlap is held.
  for (int step = 1; step < 20; ++step) capped.step();
  EXPECT_NEAR(capped.particles().position[0].y(), kRadius - 1.8 * slop, 1e-15);
  EXPECT_LT(capped.max_speed(), 1e-15);
}

// The correction's cost and effect in the account (StepReport, summary mechanics and
// energy.mechanical): a sphere 5 slops into the floor is lifted by exactly d - slop, so the
// correction made m g (d - slop) of potential energy, outside the velocity step's account
// (which stays at zero: the sphere never moves). Its travel is 0 (the lift is not motion); a
// sphere falling from rest travels h theta g h in its first step.
TEST(NscdExact, PenetrationCorrectionReportsItsPotentialEnergy) {
  NscdParameters parameters = nlgs_parameters();
  // From zero impulses, whose solve leaves the sphere exactly still; from the static warm start
  // (m g h on the floor) it moves by round-off, 6e-23 m.
  parameters.static_warm_start = false;
  const double slop = parameters.penetration_slop_fraction * kRadius;
  const double h = parameters.time_step;
  const double d = 5.0 * slop;
  const double m = sphere_mass(kRadius, kDensity);
  auto sim = single_sphere(Vector3d(0, kRadius - d, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                           0.3, parameters);
  const StepReport first = sim.step();
  ASSERT_GT(first.correction_sweeps, 0);
  const double lift = sim.particles().position[0].y() - (kRadius - d);
  EXPECT_NEAR(lift, d - slop, 1e-15);
  EXPECT_NEAR(first.correction_potential_J, m * kG * (d - slop), 1e-12 * m * kG * d);
  EXPECT_NEAR(first.correction_potential_J, m * kG * lift, 1e-12 * m * kG * d);
  EXPECT_EQ(first.energy_change_J, 0.0);
  EXPECT_EQ(first.max_travel_m, 0.0);
  for (int step = 0; step < 10; ++step) EXPECT_EQ(sim.step().correction_sweeps, 0);
  EXPECT_EQ(sim.stats().correction_sweeps, first.correction_sweeps);
  EXPECT_EQ(sim.stats().correction_potential_J, first.correction_potential_J);

  auto falling = single_sphere(Vector3d(0, 10 * kRadius, 0), {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                               0.3, parameters);
  const StepReport fall = falling.step();
  EXPECT_NEAR(fall.max_travel_m, h * parameters.theta * kG * h, 1e-15 * kG * h * h);
  EXPECT_EQ(fall.correction_potential_J, 0.0);
  EXPECT_EQ(falling.stats().max_travel_m, fall.max_travel_m);
}

// Two spheres side by side overlapping under gravity are pushed apart horizontally: the
// correction moves them but makes no potential energy (g . dx = 0 for both), to round-off.
TEST(NscdExact, SidewaysCorrectionMakesNoPotentialEnergy) {
  NscdParameters parameters = nlgs_parameters();
  const double slop = parameters.penetration_slop_fraction * kRadius;
  const double d = 20.0 * slop;
  ParticleSet set;
  set.add(Vector3d(0, kRadius, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  set.add(Vector3d(2 * kRadius - d, kRadius, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  NscdIntegrator sim(std::move(set), {steel(0.0)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, parameters);
  const StepReport report = sim.step();
  ASSERT_GT(report.correction_sweeps, 0);
  EXPECT_NEAR((sim.particles().position[1] - sim.particles().position[0]).norm(),
              2 * kRadius - slop, 1e-15);
  EXPECT_EQ(report.correction_potential_J, 0.0);
}

// Two free spheres of different masses overlapping by d (no gravity, no walls): the position
// step moves them apart along the normal in the ratio of their inverse masses, so that the
// overlap is the slop and the centre of mass stays where it was; both stay at rest.
TEST(NscdExact, OverlapOfTwoSpheresIsSharedByInverseMass) {
  NscdParameters parameters = nlgs_parameters();
  const double slop = parameters.penetration_slop_fraction * kRadius;
  const double d = 20.0 * slop;
  ParticleSet set;
  const double m0 = sphere_mass(kRadius, kDensity), m1 = sphere_mass(kRadius, 3.0 * kDensity);
  set.add(Vector3d(0, 0, 0), kRadius, m0, 0);
  set.add(Vector3d(2 * kRadius - d, 0, 0), kRadius, m1, 0);
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {}, Vector3d::Zero(), 3, parameters);
  sim.step();
  const auto& x = sim.particles().position;
  EXPECT_LT(sim.max_speed(), 1e-15);
  EXPECT_NEAR((x[1] - x[0]).norm(), 2 * kRadius - slop, 1e-15);
  // Displacements (d - slop) m1 / (m0 + m1) and (d - slop) m0 / (m0 + m1), opposite.
  EXPECT_NEAR(x[0].x(), -(d - slop) * m1 / (m0 + m1), 1e-16);
  EXPECT_NEAR(x[1].x(), 2 * kRadius - d + (d - slop) * m0 / (m0 + m1), 1e-16);
  EXPECT_NEAR(m0 * x[0].x() + m1 * x[1].x(), m1 * (2 * kRadius - d), 1e-15 * m1 * kRadius);
}
