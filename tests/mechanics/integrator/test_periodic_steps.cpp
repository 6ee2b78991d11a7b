// Steps across periodic boundaries: two spheres pushed down a slope (one sliding, one rolling)
// cross the boundary with their contact, its force the hand formula m g sin(a) / 6 before,
// while and after they cross; a pile poured into an x-z periodic box settles with every centre
// in the box and overlaps within the usual slop.
#include <gtest/gtest.h>

#include <cmath>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

const ContactForce* find_contact(const NscdIntegrator& sim, std::int32_t i, std::int32_t j) {
  for (const auto& c : sim.contacts())
    if (c.i == i && c.j == j) return &c;
  return nullptr;
}

}  // namespace

TEST(PeriodicSteps, APushedPairCrossesTheBoundaryWithItsContactAndForce) {
  // Gravity tilted by a along x over a floor y = 0. Sphere 0 is frictionless (material 1:
  // slides, acceleration g sin a alone), sphere 1 rolls (material 0, mu 0.5 on the floor:
  // (7/5) m a_1 = m g sin a + N). Touching along x they share a = (5/6) g sin a, and sphere 0
  // pushes sphere 1 with N = m (g sin a - a) = m g sin a / 6 (their contact is frictionless:
  // the smaller mu).
  const double angle = 0.1, r = kRadius;
  ParticleSet set;
  set.box.periodic = {true, false, true};
  set.box.high = Vector3d(10e-3, 0.0, 10e-3);
  const double m = sphere_mass(r, kDensity);
  set.add(Vector3d(6e-3, r, 5e-3), r, m, 1);
  set.add(Vector3d(8e-3, r, 5e-3), r, m, 0);
  NscdParameters parameters = nlgs_parameters();
  parameters.time_step = 1e-4;
  parameters.tolerance = 1e-10;
  NscdIntegrator sim(std::move(set), {steel(0.5), steel(0.0)},
                     {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(kG * std::sin(angle), -kG * std::cos(angle), 0), 3, parameters);
  const double expected_N = m * kG * std::sin(angle) / 6.0;
  int wraps[2] = {0, 0};
  double previous_x[2] = {6e-3, 8e-3};
  for (int step = 0; step < 1500; ++step) {
    const StepReport report = sim.step();
    ASSERT_TRUE(report.converged) << "step " << step;
    for (int p = 0; p < 2; ++p) {
      const double x = sim.particles().position[std::size_t(p)].x();
      ASSERT_GE(x, 0.0);
      ASSERT_LT(x, 10e-3);
      wraps[p] += x < previous_x[p];
      previous_x[p] = x;
    }
    if (step < 5) continue;  // the contact and the rolling establish themselves
    const ContactForce* pair = find_contact(sim, 0, 1);
    ASSERT_NE(pair, nullptr) << "step " << step << ": the pair lost its contact";
    EXPECT_NEAR(pair->normal_force_N, expected_N, 1e-4 * expected_N) << "step " << step;
    EXPECT_NEAR(std::abs(pair->normal.x()), 1.0, 1e-9) << "step " << step;
    EXPECT_NEAR(pair->gap_m, 0.0, 1e-9) << "step " << step;
  }
  // 0.15 s at (5/6) g sin a: 11 mm, so each sphere went round once.
  EXPECT_EQ(wraps[0], 1);
  EXPECT_EQ(wraps[1], 1);
  // Both at (5/6) g sin a t^2 / 2 from where they started, whole periods aside.
  const double t = 1500 * 1e-4, travel = 5.0 / 6.0 * kG * std::sin(angle) * t * t / 2.0;
  EXPECT_NEAR(sim.particles().position[1].x(), std::fmod(8e-3 + travel, 10e-3), 2e-6);
}

namespace {

// Two free spheres (radius 1 mm, no gravity) in a box periodic along x with a 10 mm period,
// moving apart along x at `speed` m/s each: the period leaves 10 / 2 - 2 = 3 mm for two
// particles' motion across it between rebuilds.
NscdIntegrator flying_apart(double speed) {
  ParticleSet set;
  set.box.periodic = {true, false, false};
  set.box.high = Vector3d(10e-3, 0.0, 0.0);
  const double m = sphere_mass(kRadius, kDensity);
  set.add(Vector3d(2e-3, 5e-3, 5e-3), kRadius, m, 0);
  set.add(Vector3d(6e-3, 5e-3, 5e-3), kRadius, m, 0);
  set.velocity[0] = Vector3d(-speed, 0, 0);
  set.velocity[1] = Vector3d(speed, 0, 0);
  NscdParameters parameters = nlgs_parameters();
  parameters.time_step = 1e-3;
  return NscdIntegrator(std::move(set), {steel(0.5)}, {}, Vector3d::Zero(), 3, parameters);
}

}  // namespace

// A step in which two particles could move apart across the periods by more than they allow
// is taken as two halves, the same bits as two steps of half the time step; it was refused
// before. At 1 m/s each, the look-aheads across (2 h v = 2 mm each, 4 mm together) pass the
// 3 mm of the period; at h / 2 they fit. Beyond four halvings the run stops as before: at 20
// m/s each, 5 mm together even at h / 16.
TEST(PeriodicSteps, AStepTooLongForThePeriodsIsTakenInHalves) {
  NscdIntegrator whole = flying_apart(1.0);
  NscdIntegrator halves = flying_apart(1.0);
  const StepReport report = whole.step(1e-3);
  halves.step(0.5e-3);
  halves.step(0.5e-3);
  EXPECT_EQ(whole.stats().halved_steps, 1);
  EXPECT_EQ(whole.stats().steps, 2);
  EXPECT_EQ(halves.stats().halved_steps, 0);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(whole.particles().position[i], halves.particles().position[i]) << i;
    EXPECT_EQ(whole.particles().velocity[i], halves.particles().velocity[i]) << i;
  }
  // Free flight: each sphere moved 1 mm.
  EXPECT_NEAR(whole.particles().position[1].x(), 7e-3, 1e-15);
  EXPECT_NEAR(report.max_travel_m, 1e-3, 1e-15);  // the halves' travels summed
  EXPECT_EQ(report.time_step_s, 0.5e-3);           // problem() is the second half's
  // A slower pair is not halved (1 mm each, 2 mm together).
  NscdIntegrator slow = flying_apart(0.5);
  slow.step(1e-3);
  EXPECT_EQ(slow.stats().halved_steps, 0);
  NscdIntegrator fast = flying_apart(20.0);
  EXPECT_THROW(fast.step(1e-3), std::runtime_error);
  EXPECT_EQ(fast.stats().halved_steps, NscdIntegrator::kMaxHalvings);
}
