// Particles that grow under the "hertz" normal law (what thermal expansion does to a packing,
// radii r0 (1 + alpha dT)), against closed forms: a row of spheres between two fixed walls
// carries the series-Hertz force of its growth; a column with a free top rises by its growth
// with its forces unchanged (the weights); a sphere under a piston lifts it by its growth and
// still carries the load. Radii are changed by hand (ParticleSet, invalidate_contacts), the
// packing then re-settled by steps, as the coupled mode does.
#include <gtest/gtest.h>

#include <cmath>

#include "mechanics/HertzScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

constexpr double kGrowth = 1e-3;  // alpha dT: 1e-5 1/K over 100 K

// Steps until the largest speed is below 1e-7 m/s (at most `steps`; the solves' tolerance
// leaves speeds of ~3e-8 m/s in the stiff row); every step converged.
void settle(NscdIntegrator& sim, int steps) {
  for (int s = 0; s < steps; ++s) {
    const StepReport report = sim.step();
    ASSERT_TRUE(report.converged) << "step " << s << " residual " << report.residual << " siconos " << report.siconos_residual << " sweeps " << report.sweeps << " stalled " << report.stalled;
    if (s > 10 && sim.max_speed() < 1e-7) return;
  }
  FAIL() << "not at rest after " << steps << " steps: " << sim.max_speed() << " m/s";
}

void grow(NscdIntegrator& sim, double growth) {
  for (double& r : sim.particles().radius) r *= 1.0 + growth;
  sim.invalidate_contacts();
}

double wall_force(const NscdIntegrator& sim, std::size_t wall) {
  double force = 0.0;
  for (const ContactForce& c : sim.contacts())
    if (c.j == wall_code<std::int64_t>(static_cast<std::int64_t>(wall))) force += c.normal_force_N;
  return force;
}

}  // namespace

TEST(HertzGrowth, RowBetweenFixedWallsCarriesTheSeriesHertzForceOfItsGrowth) {
  // N spheres of radius R touching in a row between walls 2 N R apart. Grown to r = R (1 + e),
  // the row is 2 N R e too long; its N - 1 sphere pairs (R* = r/2) and 2 wall contacts (R* = r)
  // carry one force F, so (N - 1) (F / K_ss)^(2/3) + 2 (F / K_sw)^(2/3) = 2 N R e.
  const int count = 5;
  ParticleSet set;
  for (int k = 0; k < count; ++k)
    set.add(Vector3d((2 * k + 1) * kRadius, 0, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  NscdIntegrator sim(std::move(set), {steel(0.3)},
                     {Wall::through({0, 0, 0}, {1, 0, 0}, 0),
                      Wall::through({2 * count * kRadius, 0, 0}, {-1, 0, 0}, 0)},
                     Vector3d::Zero(), 3, hertz_parameters());
  grow(sim, kGrowth);
  settle(sim, 20000);
  const double r = kRadius * (1 + kGrowth), modulus = steel_pair_modulus();
  const double k_pair = hertz_coefficient(modulus, r / 2), k_wall = hertz_coefficient(modulus, r);
  const double compliance = (count - 1) * std::pow(k_pair, -2.0 / 3.0) + 2 * std::pow(k_wall, -2.0 / 3.0);
  const double force = std::pow(2 * count * kRadius * kGrowth / compliance, 1.5);  // 34 N here
  EXPECT_NEAR(wall_force(sim, 0), force, 1e-6 * force);
  EXPECT_NEAR(wall_force(sim, 1), force, 1e-6 * force);
  for (const ContactForce& c : sim.contacts()) EXPECT_NEAR(c.normal_force_N, force, 1e-6 * force);
}

TEST(HertzGrowth, ColumnWithAFreeTopRisesByItsGrowthWithItsWeightsUnchanged) {
  // N spheres stacked on the floor under gravity: contact k (from the top, 1-based) carries the
  // weight of the k spheres above it, before and after growth; the top centre sits at
  // r + sum over contacts of (2 r or r) - overlaps, each overlap (k m g / K)^(2/3).
  const int count = 5;
  const double mass = sphere_mass(kRadius, kDensity), weight = mass * kG;
  ParticleSet set;
  for (int k = 0; k < count; ++k) set.add(Vector3d(0, (2 * k + 1) * kRadius, 0), kRadius, mass, 0);
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, hertz_parameters());
  settle(sim, 20000);
  grow(sim, kGrowth);
  settle(sim, 20000);
  const double r = kRadius * (1 + kGrowth), modulus = steel_pair_modulus();
  double top = r - std::cbrt(std::pow(count * weight / hertz_coefficient(modulus, r), 2.0));
  for (int k = 1; k < count; ++k)  // sphere pair k from the top carries k weights
    top += 2 * r - std::cbrt(std::pow(k * weight / hertz_coefficient(modulus, r / 2), 2.0));
  EXPECT_NEAR(sim.particles().position[count - 1].y(), top, 1e-12);
  EXPECT_NEAR(wall_force(sim, 0), count * weight, 1e-9 * count * weight);
  for (const ContactForce& c : sim.contacts()) {
    // The floor carries every sphere; the pair (i, i + 1) the spheres from i + 1 up.
    const int above = count - static_cast<int>(is_wall(c.j) ? c.i : c.j);
    EXPECT_NEAR(c.normal_force_N, above * weight, 1e-9 * count * weight) << "sphere " << c.i;
  }
}

TEST(HertzGrowth, SphereUnderAPistonLiftsItByItsGrowth) {
  // One sphere between the floor and a piston of load L (no gravity): two contacts of R* = r in
  // series, the piston at 2 r - 2 (L / K)^(2/3); the force stays L.
  const double load = 10.0;
  ParticleSet set;
  set.add(Vector3d(0, kRadius, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  Wall piston = Wall::through({0, 2 * kRadius, 0}, {0, -1, 0}, 0);
  piston.make_piston(1e-3, load);
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston},
                     Vector3d::Zero(), 3, hertz_parameters());
  settle(sim, 20000);
  const double modulus = steel_pair_modulus();
  const double before = 2 * kRadius - 2 * hertz_overlap(hertz_coefficient(modulus, kRadius), load);
  EXPECT_NEAR(sim.walls()[1].point.y(), before, 1e-5 * (2 * kRadius - before));
  grow(sim, kGrowth);
  settle(sim, 20000);
  const double r = kRadius * (1 + kGrowth);
  const double after = 2 * r - 2 * hertz_overlap(hertz_coefficient(modulus, r), load);
  EXPECT_NEAR(sim.walls()[1].point.y(), after, 1e-5 * (2 * r - after));
  EXPECT_NEAR(wall_force(sim, 1), load, 1e-8 * load);
}
