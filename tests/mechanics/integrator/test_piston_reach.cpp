// A loaded piston's candidates listed with its likely reach (NscdParameters::estimate_wall_reach):
// the same statics as with the bound on a pressed column, on a table a fraction of the size; and
// a bed that gives way under the load, where the travel leaves the estimated table, listed again
// with the bound, every step ending with no pair overlapping beyond the slop (checked against
// every pair, listed or not).
#include <gtest/gtest.h>

#include <algorithm>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// The deepest overlap of any pair of spheres or of a sphere with a wall, m (>= 0), whether the
// table listed the pair or not.
double deepest_overlap_m(const NscdIntegrator& sim) {
  const ParticleSet& p = sim.particles();
  double deepest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j)
      deepest = std::max(deepest, p.radius[i] + p.radius[j] - (p.position[i] - p.position[j]).norm());
    for (const Wall& w : sim.walls()) deepest = std::max(deepest, p.radius[i] - w.signed_distance(p.position[i]));
  }
  return deepest;
}

// `count` steel spheres of radius R stacked along y on the floor between side walls x = +-R, a
// 1 g piston resting on the top one pressed with 20 N: its bound reach 2 h^2 F / m is 40 mm
// (20 radii) at h = 1 ms, so once engaged every pair of the column is listed.
NscdIntegrator pressed_column(int count, bool estimate) {
  ParticleSet set;
  for (int k = 0; k < count; ++k)
    set.add(Vector3d(0, kRadius * (2 * k + 1), 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  Wall piston = Wall::through({0, 2 * count * kRadius, 0}, {0, -1, 0}, 0);
  piston.make_piston(1e-3, 20.0);
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-10;
  parameters.max_iterations = 100000;
  parameters.estimate_wall_reach = estimate;
  return NscdIntegrator(std::move(set), {steel(0.0)},
                        {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston,
                         Wall::through({-kRadius, 0, 0}, {1, 0, 0}, 0),
                         Wall::through({kRadius, 0, 0}, {-1, 0, 0}, 0)},
                        Vector3d(0, -kG, 0), 3, parameters);
}

}  // namespace

TEST(PistonReach, APressedColumnKeepsItsStaticsOnAFractionOfTheCandidates) {
  const int count = 16;
  NscdIntegrator bound = pressed_column(count, false), likely = pressed_column(count, true);
  std::size_t bound_candidates = 0, likely_candidates = 0;
  for (int s = 0; s < 50; ++s) {
    bound_candidates = bound.step().candidates;
    likely_candidates = likely.step().candidates;
    ASSERT_LT(deepest_overlap_m(likely), 2e-4 * kRadius) << "step " << s + 1;
  }
  // The bound lists every pair of the column (16 x 15 / 2) and the walls'; the likely reach the
  // touching neighbours and the walls beside them.
  EXPECT_GE(bound_candidates, std::size_t(count * (count - 1) / 2));
  EXPECT_LT(likely_candidates, bound_candidates / 3);
  EXPECT_EQ(likely.stats().relisted_steps, 0);  // a column that holds never leaves its table
  // Every contact carries what is above it (frictionless: the statics are unique), as with the bound.
  const double weight_N = sphere_mass(kRadius, kDensity) * kG, load_N = 20.0 + 1e-3 * kG;
  double floor_bound = 0.0, floor_likely = 0.0;
  for (const ContactForce& f : bound.contacts()) if (f.j == wall_code<std::int64_t>(0)) floor_bound = f.normal_force_N;
  for (const ContactForce& f : likely.contacts()) if (f.j == wall_code<std::int64_t>(0)) floor_likely = f.normal_force_N;
  EXPECT_NEAR(floor_likely, load_N + count * weight_N, 1e-8 * floor_likely);
  EXPECT_NEAR(floor_likely, floor_bound, 1e-8 * floor_bound);
  EXPECT_NEAR(likely.walls()[1].point.y(), bound.walls()[1].point.y(), 1e-9 * kRadius);
  EXPECT_NEAR(likely.max_speed(), bound.max_speed(), 1e-9);  // the same creep at this tolerance
}

TEST(PistonReach, ABedThatGivesWayIsListedAgainWithTheBound) {
  // A frictionless sphere balanced on a fixed one, 1e-14 R off its top, a 1 g piston resting on
  // it pressed with 20 N: the balance holds for five steps (the offset grows about e^25-fold a
  // step), then gives way within one, the sphere thrown out at 28 m/s and the piston dropping
  // 2 R: travel far beyond what the last step's push foretold. Those steps are listed again with
  // the bound; every step ends with no pair overlapping beyond the slop, listed or not, and the
  // run follows the bound's.
  const auto balanced = [](bool estimate) {
    ParticleSet set;
    const double m = sphere_mass(kRadius, kDensity);
    set.add(Vector3d(0, kRadius, 0), kRadius, m, 0, true);
    set.add(Vector3d(1e-14 * kRadius, 3 * kRadius, 0), kRadius, m, 0);
    Wall piston = Wall::through({0, 4 * kRadius, 0}, {0, -1, 0}, 0);
    piston.make_piston(1e-3, 20.0);
    NscdParameters parameters = nlgs_parameters();
    parameters.tolerance = 1e-10;
    parameters.max_iterations = 100000;
    parameters.estimate_wall_reach = estimate;
    return NscdIntegrator(std::move(set), {steel(0.0)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston},
                          Vector3d(0, -kG, 0), 3, parameters);
  };
  NscdIntegrator bound = balanced(false), likely = balanced(true);
  for (int s = 0; s < 12; ++s) {
    bound.step();
    const StepReport report = likely.step();
    EXPECT_EQ(report.relisted, s == 5 || s == 6) << "step " << s + 1;
    ASSERT_LT(deepest_overlap_m(likely), 1e-6 * kRadius) << "step " << s + 1;
    EXPECT_NEAR(likely.walls()[1].point.y(), bound.walls()[1].point.y(), 1e-9 * kRadius) << "step " << s + 1;
    EXPECT_NEAR((likely.particles().position[1] - bound.particles().position[1]).norm(), 0.0, 1e-9 * kRadius);
  }
  EXPECT_EQ(likely.stats().relisted_steps, 2);
  EXPECT_NEAR(likely.walls()[1].point.y(), 2 * kRadius, 1e-6 * kRadius);  // on the fixed sphere
  EXPECT_GT(std::abs(likely.particles().velocity[1].x()), 20.0);       // thrown out
}
