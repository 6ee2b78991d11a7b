// At rest means at rest (issue 10): a settled pile carries exactly its weight on the floor and
// stays where it is, and frictionless stacks carry their closed-form static forces.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/model/PairIndex.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// 40 disks (radii 1 and 0.7 mm) dropped at random into a 2D box 8 mm wide (about six
// layers), floor mu = 0.5, side walls frictionless (material 1, mu = 0), stepped until every
// speed is below 1e-9 m/s. The solver runs at tolerance 1e-8: a solve converged to a relative
// residual eps leaves velocity errors of about eps times the impulses over the masses, i.e.
// eps g h (1e-6 x 9.81e-3 = 1e-8 m/s at the default), which would be the whole allowance of
// the rest test below; at 1e-8 the pile's largest speed stays about 1e-9 m/s.
NscdIntegrator settled_pile() {
  NscdIntegrator sim = settled_disk_pile();
  EXPECT_LT(sim.max_speed(), 1e-9) << "the pile did not settle within 5 s";
  return sim;
}

double total_weight_N(const NscdIntegrator& sim) {
  double weight = 0.0;
  for (double m : sim.particles().mass) weight += m * kG;
  return weight;
}

}  // namespace

// Side walls without friction take no vertical load, so at rest the floor carries the whole
// weight: sum of floor reactions = M g up to the momentum change of one step (M dv / h with
// dv < 1e-8 m/s: 1e-6 of M g at h = 1 ms). Every reaction lies in its Coulomb cone (mu = 0.5
// between disks and with the floor, 0 with the side walls).
TEST(NscdRest, FloorCarriesTheWholeWeightOfARestingPile) {
  auto sim = settled_pile();
  sim.step();
  double floor_N = 0.0;
  std::size_t on_floor = 0;
  for (const ContactForce& c : sim.contacts()) {
    const bool side_wall = is_wall(c.j) && c.j != wall_code<std::int64_t>(0);
    const double mu = side_wall ? 0.0 : 0.5;
    ASSERT_GE(c.normal_force_N, 0.0);
    ASSERT_LE(c.tangential_force_N.norm(), mu * c.normal_force_N * (1 + 1e-9))
        << "contact " << c.i << "-" << c.j;
    if (c.j == wall_code<std::int64_t>(0)) {
      floor_N += c.normal_force_N * c.normal.y() + c.tangential_force_N.y();
      ++on_floor;
    }
  }
  EXPECT_GE(on_floor, 4u);
  EXPECT_NEAR(floor_N, total_weight_N(sim), 1e-6 * total_weight_N(sim));
}

// The same pile stepped 10,000 more steps (10 s) stays exactly where it is: no speed builds
// up (penetration is removed by moving positions only, never as a push-out speed), and no
// particle moves by more than 1e-9 m.
TEST(NscdRest, RestingPileStaysAtRestFor10000Steps) {
  auto sim = settled_pile();
  const Drift drift = drift_over(sim, 10000);
  EXPECT_LT(drift.fastest_m_per_s, 1e-8);
  EXPECT_LT(drift.moved_m, 1e-9);
  // Over the whole run (settling included) no overlap went deeper than twice the slop, the
  // depth at which the position step corrects (PenetrationCorrection.h), up to that step's
  // 1% tolerance.
  EXPECT_LE(sim.stats().max_penetration_m, PenetrationCorrection::kTrigger *
                                               sim.parameters().penetration_slop_fraction *
                                               0.7 * kRadius * (1 + 1e-2));
}

namespace {

// Normal force of every contact carrying load after one step from rest, by pair (i, j).
std::map<std::pair<std::int64_t, std::int64_t>, double> forces_after_one_step(NscdIntegrator& sim) {
  sim.step();
  std::map<std::pair<std::int64_t, std::int64_t>, double> out;
  for (const ContactForce& c : sim.contacts()) out[{c.i, c.j}] = c.normal_force_N;
  return out;
}

NscdParameters tight() {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-12;
  return parameters;
}

}  // namespace

// Frictionless 2D stack of six equal disks, rows 3-2-1, in a box whose side walls touch the
// bottom row. The disks of a row are spread to a spacing s = 2.2 R (not touching: with
// touching rows, as in a hexagonal packing, the frictionless forces are not unique), so each
// disk above rests on two below at phi from the vertical, sin phi = s / (4 R).
// Statics, top down (m g the weight of one disk):
//   top: two contacts N1, 2 N1 cos phi = m g               -> N1 = m g / (2 cos phi);
//   left disk of row 2 (the right one by symmetry): loaded by N1 from the top (down and
//     outwards); supports A (outer) and B (inner): vertical (A + B) cos phi = m g + N1 cos phi,
//     horizontal (A - B) sin phi = N1 sin phi                -> A = 2 N1, B = N1;
//   bottom row: floor under each disk = m g + 2 N1 cos phi = 2 m g (outer: m g + A cos phi;
//     middle: m g + 2 B cos phi); side walls A sin phi = m g tan phi.
// Total on the floor 6 m g. Contacts within rows carry nothing.
TEST(NscdRest, FrictionlessStackOfDisksCarriesItsClosedFormForces) {
  const double R = kRadius, s = 2.2 * R;
  const double sin_phi = s / (4 * R), cos_phi = std::sqrt(1 - sin_phi * sin_phi);
  const double rise = 2 * R * cos_phi;
  ParticleSet set;
  const double m = sphere_mass(R, kDensity), mg = m * kG;
  for (int k = 0; k < 3; ++k) set.add(Vector3d(R + k * s, R, 0), R, m, 0);              // 0-2
  for (int k = 0; k < 2; ++k) set.add(Vector3d(R + (k + 0.5) * s, R + rise, 0), R, m, 0);  // 3-4
  set.add(Vector3d(R + s, R + 2 * rise, 0), R, m, 0);                                    // 5
  const double width = 2 * R + 2 * s;
  NscdIntegrator sim(std::move(set), {steel(0.0)}, box_walls(width, width, 2),
                     Vector3d(0, -kG, 0), 2, tight());
  auto forces = forces_after_one_step(sim);
  const double N1 = mg / (2 * cos_phi);
  const std::int64_t floor = wall_code<std::int64_t>(0), left = wall_code<std::int64_t>(1),
                     right = wall_code<std::int64_t>(2);
  const std::map<std::pair<std::int64_t, std::int64_t>, double> expected = {
      {{3, 5}, N1},       {{4, 5}, N1},                       // top
      {{0, 3}, 2 * N1},   {{1, 3}, N1},                       // left disk of row 2
      {{1, 4}, N1},       {{2, 4}, 2 * N1},                   // right disk of row 2
      {{0, floor}, 2 * mg}, {{1, floor}, 2 * mg}, {{2, floor}, 2 * mg},
      {{0, left}, mg * sin_phi / cos_phi}, {{2, right}, mg * sin_phi / cos_phi}};
  for (const auto& [pair, force] : expected) {
    ASSERT_TRUE(forces.contains(pair)) << pair.first << "-" << pair.second;
    EXPECT_NEAR(forces[pair], force, 1e-9 * mg) << pair.first << "-" << pair.second;
  }
  EXPECT_EQ(forces.size(), expected.size());  // nothing else carries load
  EXPECT_LT(sim.max_speed(), 1e-12);  // solved to 1e-12 of the impulses m g h
}

// Frictionless 3D pyramid of four equal spheres: three on the floor at the corners of an
// equilateral triangle of side s = 2.2 R (not touching each other), each held by a vertical
// wall on its outer side, and one on top. The top rests on the three at phi from the
// vertical, sin phi = d / (2 R) with d = s / sqrt(3) the triangle's circumradius.
// Statics: top 3 N cos phi = m g -> N = m g / (3 cos phi); each base sphere: floor
// m g + N cos phi = 4/3 m g, its wall N sin phi = (m g / 3) tan phi.
TEST(NscdRest, FrictionlessPyramidOfSpheresCarriesItsClosedFormForces) {
  const double R = kRadius, s = 2.2 * R, d = s / std::sqrt(3.0);
  const double sin_phi = d / (2 * R), cos_phi = std::sqrt(1 - sin_phi * sin_phi);
  const Vector3d centre(0.01, R, 0.01);
  ParticleSet set;
  const double m = sphere_mass(R, kDensity), mg = m * kG;
  std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0)};
  for (int k = 0; k < 3; ++k) {
    const double angle = 2 * std::numbers::pi * k / 3;
    const Vector3d e(std::cos(angle), 0, std::sin(angle));
    set.add(centre + d * e, R, m, 0);
    walls.push_back(Wall::through(centre + (d + R) * e, -e, 0));
  }
  set.add(centre + Vector3d(0, 2 * R * cos_phi, 0), R, m, 0);
  NscdIntegrator sim(std::move(set), {steel(0.0)}, walls, Vector3d(0, -kG, 0), 3, tight());
  auto forces = forces_after_one_step(sim);
  const double N = mg / (3 * cos_phi);
  for (std::int64_t k = 0; k < 3; ++k) {
    const auto wall = [k](std::size_t w) { return std::pair{k, wall_code<std::int64_t>(w)}; };
    const double top = forces[std::make_pair(k, std::int64_t(3))];
    EXPECT_NEAR(top, N, 1e-9 * mg) << "top on " << k;
    EXPECT_NEAR(forces[wall(0)], 4.0 / 3.0 * mg, 1e-9 * mg) << "floor under " << k;
    EXPECT_NEAR(forces[wall(std::size_t(k) + 1)], N * sin_phi, 1e-9 * mg) << "wall of " << k;
  }
  EXPECT_EQ(forces.size(), 9u);
  EXPECT_LT(sim.max_speed(), 1e-12);  // solved to 1e-12 of the impulses m g h
}
