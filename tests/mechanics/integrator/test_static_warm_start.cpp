// The first step's warm start from the statics of the contact geometry (StaticWarmStart.h):
// closed-form statics of a pyramid and of a column, what it leaves out, the sweeps it saves
// on a deep column, and a falling bed (nothing under it) that it leaves without loads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "mechanics/ColumnStatics.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/integrator/StaticWarmStart.h"
#include "mechanics/model/PairIndex.h"
#include "mechanics/model/SequentialDeposition.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {


// One contact of a hand-made problem: body j a particle or wall_code(w), n from j to i.
void add_contact(ContactProblem& p, std::int32_t i, std::int32_t j, const Vector3d& n) {
  const std::size_t c = p.size();
  p.resize_contacts(c + 1);
  p.body_i[c] = i;
  p.body_j[c] = j;
  p.normal[c] = n.normalized();
  p.w_n[c] = 1.0;
  p.mu[c] = 0.0;
  p.lever_i[c] = 1e-3;  // m, the spheres' radius
}

}  // namespace

// Four equal spheres: three on the floor, touching each other, one on top in their pocket
// (phi from the vertical, cos phi = sqrt(2/3)). Statics of the top: three contacts of
// m g / (3 cos phi). Each base sphere is pushed down by m g / 3 and outwards by (m g / 3) tan phi;
// the floor takes 4/3 m g, and the outward push (which friction holds) is left to the solver:
// the contacts within the base, horizontal, carry nothing.
TEST(StaticWarmStart, PyramidCarriesItsVerticalStaticsAndLeavesTheRest) {
  const double R = 1e-3, m = 1e-5, g = 9.81, h = 1e-3, mg = m * g;
  const double cos_phi = std::sqrt(2.0 / 3.0);
  std::vector<Vector3d> x;
  for (int k = 0; k < 3; ++k) {
    const double angle = 2 * std::numbers::pi * k / 3;
    x.push_back(Vector3d(std::cos(angle), 0, std::sin(angle)) * (2 * R / std::sqrt(3.0)) +
                Vector3d(0, R, 0));
  }
  x.push_back(Vector3d(0, R + 2 * R * cos_phi, 0));
  ContactProblem p;
  p.inverse_mass.assign(4, 1.0 / m);
  p.inverse_inertia.assign(4, 1.0);
  p.free_velocity.assign(4, Vector3d::Zero());
  p.free_angular_velocity.assign(4, Vector3d::Zero());
  p.add_fixed_wall_bodies(1);
  for (std::int32_t k = 0; k < 3; ++k) add_contact(p, k, wall_code<std::int32_t>(0), {0, 1, 0});
  add_contact(p, 0, 1, x[0] - x[1]);
  add_contact(p, 0, 2, x[0] - x[2]);
  add_contact(p, 1, 2, x[1] - x[2]);
  for (std::int32_t k = 0; k < 3; ++k) add_contact(p, k, 3, x[std::size_t(k)] - x[3]);
  const std::vector<double> gaps(p.size(), 0.0);
  std::vector<Vector3d> r;
  static_warm_start(p, gaps, x, Vector3d(0, -g, 0), h, r);
  ASSERT_EQ(r.size(), p.size());
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(r[c][0], 4.0 / 3.0 * mg * h, 1e-12 * mg * h);
  for (std::size_t c = 3; c < 6; ++c) EXPECT_EQ(r[c][0], 0.0) << "base contact " << c;
  for (std::size_t c = 6; c < 9; ++c) EXPECT_NEAR(r[c][0], mg * h / (3 * cos_phi), 1e-12 * mg * h);
  for (const auto& reaction : r) EXPECT_EQ(reaction.tail<2>().norm(), 0.0);

  // Not touching (a gap of 2e-6 radii): nothing; no gravity: nothing.
  std::vector<double> apart(p.size(), 2e-6 * R);
  static_warm_start(p, apart, x, Vector3d(0, -g, 0), h, r);
  for (const auto& reaction : r) EXPECT_EQ(reaction.norm(), 0.0);
  static_warm_start(p, gaps, x, Vector3d::Zero(), h, r);
  for (const auto& reaction : r) EXPECT_EQ(reaction.norm(), 0.0);
}

// A column of 40 equal spheres on the floor: Gauss-Seidel from zero impulses passes the weights
// down a contact or so per sweep; the static start is the column's statics already, and the
// first step confirms it in a sweep or two.
TEST(StaticWarmStart, DeepColumnStartsAtItsStaticsAndSavesTheSweeps) {
  std::vector<double> masses;
  for (int k = 0; k < 40; ++k) masses.push_back(1e-5);
  auto first_step = [&](bool static_start) {
    ParticleSet set;
    for (std::size_t k = 0; k < masses.size(); ++k)
      set.add(Vector3d(0.0, (2.0 * double(k) + 1.0) * kRadius, 0.0), kRadius, masses[k], 0);
    NscdParameters parameters = nlgs_parameters();
    parameters.tolerance = 1e-8;
    parameters.static_warm_start = static_start;
    NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                       Vector3d(0, -kG, 0), 3, parameters);
    const StepReport report = sim.step();
    if (static_start) {
      EXPECT_TRUE(report.converged);
      expect_column_statics(sim, sim.reactions(), 1e-8);
    }
    return report.sweeps;
  };
  const int cold = first_step(false), warm = first_step(true);
  EXPECT_LE(warm, 3);
  EXPECT_GE(cold, 100);  // 7,957 when written
  std::printf("first step of a 40-sphere column: %d sweeps from zero, %d from the statics\n", cold, warm);
}

// A pyramid in the air beside a sphere on the floor: the pyramid falls freely, so its contacts
// carry nothing (passing its weight down would leave its base spheres pushed down by a load no
// floor takes), while the sphere on the floor carries its own weight.
TEST(StaticWarmStart, FallingClusterCarriesNothing) {
  const double R = 1e-3, m = 1e-5, g = 9.81, h = 1e-3, lift_m = 1e-3;
  const double cos_phi = std::sqrt(2.0 / 3.0);
  std::vector<Vector3d> x;
  for (int k = 0; k < 3; ++k) {
    const double angle = 2 * std::numbers::pi * k / 3;
    x.push_back(Vector3d(std::cos(angle), 0, std::sin(angle)) * (2 * R / std::sqrt(3.0)) +
                Vector3d(0, R + lift_m, 0));
  }
  x.push_back(Vector3d(0, R + lift_m + 2 * R * cos_phi, 0));
  x.push_back(Vector3d(10 * R, R, 0));  // on the floor, apart
  ContactProblem p;
  p.inverse_mass.assign(5, 1.0 / m);
  p.inverse_inertia.assign(5, 1.0);
  p.free_velocity.assign(5, Vector3d::Zero());
  p.free_angular_velocity.assign(5, Vector3d::Zero());
  p.add_fixed_wall_bodies(1);
  // The floor is a candidate of the pyramid's base (a gap of lift_m) and touches sphere 4.
  for (std::int32_t k = 0; k < 3; ++k) add_contact(p, k, wall_code<std::int32_t>(0), {0, 1, 0});
  add_contact(p, 4, wall_code<std::int32_t>(0), {0, 1, 0});
  add_contact(p, 0, 1, x[0] - x[1]);
  add_contact(p, 0, 2, x[0] - x[2]);
  add_contact(p, 1, 2, x[1] - x[2]);
  for (std::int32_t k = 0; k < 3; ++k) add_contact(p, k, 3, x[std::size_t(k)] - x[3]);
  std::vector<double> gaps(p.size(), 0.0);
  for (std::size_t c = 0; c < 3; ++c) gaps[c] = lift_m;
  std::vector<Vector3d> r;
  static_warm_start(p, gaps, x, Vector3d(0, -g, 0), h, r);
  ASSERT_EQ(r.size(), p.size());
  for (std::size_t c = 0; c < p.size(); ++c) {
    if (c == 3) continue;  // sphere 4 on the floor
    EXPECT_EQ(r[c].norm(), 0.0) << "contact " << c << " of the falling pyramid";
  }
  EXPECT_NEAR(r[3][0], m * g * h, 1e-12 * m * g * h);
}

// A bed laid by deposition 1 mm above the floor of a box periodic along x and z, a piston high
// above it (the piston's fast fall widens the candidates' margin, so the floor is a candidate
// of the lowest spheres): the bed falls freely in its first step, every sphere at g h with no
// contact force. Loads passed down into its lowest spheres (which nothing carries) had sent the
// solver from a start far from that answer, and it diverged (speeds of 1e10 m/s).
TEST(StaticWarmStart, BedDepositedAboveTheFloorFallsFreely) {
  const double period_m = 0.02, lift_m = 1e-3, h = 1e-3;
  std::vector<double> radii;
  for (int k = 0; k < 200; ++k) radii.push_back(k % 2 ? 0.8e-3 : 1e-3);
  const auto laid = deposit_spheres(radii, Vector3d(0, lift_m, 0), Vector3d(period_m, 0.09, period_m),
                                    1, -1, 11, 3, {}, {}, {true, false, true});
  ParticleSet set;
  set.box.periodic = {true, false, true};
  set.box.high = Vector3d(period_m, 0.0, period_m);
  for (std::size_t k = 0; k < radii.size(); ++k)
    set.add(laid.positions[k], radii[k], sphere_mass(radii[k], 2500.0), 0);
  Wall piston = Wall::through({0, 0.095, 0}, {0, -1, 0}, 0);
  piston.make_piston(0.01, 4.0);
  NscdParameters parameters = nlgs_parameters();
  parameters.time_step = h;
  parameters.solver = "nncg";
  NscdIntegrator sim(std::move(set), {Material{2500.0, 6.3e10, 0.22, 0.3}},
                     {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston}, Vector3d(0, -kG, 0), 3,
                     parameters);
  const StepReport report = sim.step();
  EXPECT_TRUE(report.converged) << report.sweeps << " sweeps, residual " << report.residual;
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    ASSERT_NEAR(sim.particles().velocity[i].y(), -kG * h, 1e-6 * kG * h) << "sphere " << i;
  for (const auto& reaction : sim.reactions()) EXPECT_LE(reaction.norm(), 1e-6 * 1e-5 * kG * h);
}

// A sphere in an asymmetric V of two fixed walls (inclined by a and b from the horizontal). The
// vertical start shares the weight by the walls' rises alone and leaves the sphere pushed
// sideways; balanced (NscdParameters::static_balance_rounds), it is the V's exact statics:
// N1 = m g sin b / sin(a + b), N2 = m g sin a / sin(a + b) along the normals, up to a small
// self-stress along the line through the two contact points.
TEST(StaticWarmStart, BalancedStartIsTheStaticsOfAnAsymmetricV) {
  const double R = 1e-3, m = 1e-5, g = 9.81, h = 1e-3, mg = m * g;
  const double a = 0.3, b = 0.9;  // rad
  ContactProblem p;
  p.inverse_mass.assign(1, 1.0 / m);
  p.inverse_inertia.assign(1, 1.0 / (0.4 * m * R * R));
  p.free_velocity.assign(1, Vector3d(0, -g * h, 0));  // at rest, one step of gravity
  p.free_angular_velocity.assign(1, Vector3d::Zero());
  p.add_fixed_wall_bodies(2);
  add_contact(p, 0, wall_code<std::int32_t>(0), {std::sin(a), std::cos(a), 0});
  add_contact(p, 0, wall_code<std::int32_t>(1), {-std::sin(b), std::cos(b), 0});
  for (std::size_t c = 0; c < p.size(); ++c) {
    p.tangent1[c] = p.normal[c].unitOrthogonal();
    p.tangent2[c] = p.normal[c].cross(p.tangent1[c]);
    p.mu[c] = 0.5;
  }
  const std::vector<Vector3d> x{Vector3d(0, R, 0)};
  const std::vector<double> gaps(p.size(), 0.0);
  // The sphere's momentum change, from each reaction applied as the solvers apply it.
  auto net_impulse = [&](const std::vector<Vector3d>& r) {
    std::vector<Vector3d> v{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
    std::vector<Vector3d> w(v);
    for (std::size_t c = 0; c < p.size(); ++c) apply_impulse(p, c, r[c], v, w);
    return Vector3d(m * v[0]);
  };
  std::vector<Vector3d> vertical, balanced;
  static_warm_start(p, gaps, x, Vector3d(0, -g, 0), h, vertical);
  static_warm_start(p, gaps, x, Vector3d(0, -g, 0), h, balanced, 1);
  // The vertical start carries the weight but pushes the sphere sideways.
  EXPECT_NEAR(net_impulse(vertical).y(), mg * h, 1e-12 * mg * h);
  EXPECT_GT(std::abs(net_impulse(vertical).x()), 0.1 * mg * h);
  // Balanced: at rest after the step, to the regularisation's 1e-6.
  EXPECT_NEAR(net_impulse(balanced).norm() - mg * h, 0.0, 1e-5 * mg * h);
  EXPECT_NEAR(net_impulse(balanced).y(), mg * h, 1e-5 * mg * h);
  // The balanced impulses are the statics up to the one self-stress two point contacts allow:
  // equal and opposite impulses along the line through the contact points (p_k = -R n_k), which
  // the least change takes only a little of (its tangential part is costly).
  const Vector3d statics[2] = {mg * h * std::sin(b) / std::sin(a + b) * p.normal[0],
                               mg * h * std::sin(a) / std::sin(a + b) * p.normal[1]};
  Vector3d extra[2];
  for (std::size_t c = 0; c < 2; ++c)
    extra[c] = balanced[c][0] * p.normal[c] + balanced[c][1] * p.tangent1[c] + balanced[c][2] * p.tangent2[c] -
               statics[c];
  const Vector3d line = (p.normal[1] - p.normal[0]).normalized();  // p_0 - p_1, over R
  EXPECT_LE((extra[0] + extra[1]).norm(), 1e-5 * mg * h);
  EXPECT_LE(extra[0].cross(line).norm(), 1e-5 * mg * h);
  EXPECT_LE(extra[0].norm(), 1e-3 * mg * h);
  for (std::size_t c = 0; c < 2; ++c) EXPECT_LE(balanced[c].tail<2>().norm(), p.mu[c] * balanced[c][0]);
}

// The balance on a deposited bed in a narrow shaft (its side walls' friction carries part of the
// weight): the first step converges from it in fewer sweeps than from the vertical start (166
// and 144 when written).
TEST(StaticWarmStart, BalancedStartOfAShaftSavesSweeps) {
  // Steel spheres of 1 mm laid in a 3 x 3 mm shaft, about 30 layers (friction 0.5).
  const double width_m = 3e-3, radius_m = 0.5e-3;
  const std::vector<double> radii(300, radius_m);
  const auto laid = deposit_spheres(radii, Vector3d(0, 0, 0), Vector3d(width_m, 0.1, width_m), 1, -1, 7);
  auto first_step = [&](int rounds) {
    ParticleSet set;
    for (std::size_t k = 0; k < radii.size(); ++k)
      set.add(laid.positions[k], radii[k], sphere_mass(radii[k], 7800.0), 0);
    NscdParameters parameters;
    parameters.static_balance_rounds = rounds;
    std::vector<Wall> walls{Wall::through({0, 0, 0}, {0, 1, 0}, 0), Wall::through({0, 0, 0}, {1, 0, 0}, 0),
                            Wall::through({width_m, 0, 0}, {-1, 0, 0}, 0), Wall::through({0, 0, 0}, {0, 0, 1}, 0),
                            Wall::through({0, 0, width_m}, {0, 0, -1}, 0)};
    NscdIntegrator sim(std::move(set), {Material{7800.0, 2.1e11, 0.3, 0.5}}, walls, Vector3d(0, -kG, 0), 3,
                       parameters);
    const StepReport report = sim.step();
    EXPECT_TRUE(report.converged) << rounds << " rounds";
    return report.sweeps;
  };
  const int vertical = first_step(0), balanced = first_step(4);
  std::printf("first step of a deposited shaft: %d sweeps from the vertical start, %d balanced\n", vertical,
              balanced);
  EXPECT_LT(balanced, vertical);
}
