// Rolling resistance (Material::rolling_friction, ContactProblem.h): a contact resists the
// relative rolling of its bodies with an angular impulse up to mu_r R_eff r_n. Checked against
// closed-form rigid-body answers; the Moreau-Jean scheme is exact for these constant forces.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <stdexcept>

#include "mechanics/SameBits.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/solvers/ApgdSolver.h"
#include "mechanics/solvers/ColouredGaussSeidelSolver.h"
#include "mechanics/solvers/GaussSeidelSolver.h"
#include "mechanics/contact/NaturalMapResidual.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

using tmdem::mechanics::test::same_bits;

Material rolling_steel(double friction, double rolling_friction) {
  Material m = steel(friction);
  m.rolling_friction = rolling_friction;
  return m;
}

NscdParameters rolling_tight(const char* solver = "nlgs") {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-13;
  parameters.solver = solver;
  return parameters;
}

// One sphere touching the floor y = 0, gravity g (sin a, -cos a, 0): an incline of angle a.
NscdIntegrator sphere_on_floor(double friction, double rolling_friction, double angle,
                               int dimension, const char* solver = "nlgs") {
  ParticleSet set;
  set.add(Vector3d(0.01, kRadius, dimension == 3 ? 0.01 : 0.0), kRadius,
          sphere_mass(kRadius, kDensity), 0);
  return NscdIntegrator(std::move(set), {rolling_steel(friction, rolling_friction)},
                        {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                        Vector3d(kG * std::sin(angle), -kG * std::cos(angle), 0), dimension,
                        rolling_tight(solver));
}

class RollingSphere : public ::testing::TestWithParam<std::tuple<int, const char*>> {};

}  // namespace

// A sphere rolling without slip on a level floor at v0, mu_r = 0.1 (mu = 0.5 keeps it from
// slipping). The rolling torque M = mu_r R m g against I dw/dt and the friction force give
//   a = -R M / (I + m R^2) = -5/7 mu_r g,
// so v falls by 5/7 mu_r g h per step and the sphere stops after v0 / |a| at the distance
// v0^2 / (2 |a|) (the theta = 1/2 position update is exact for a linear velocity). v0 is a
// whole number N of steps' decrements, so the sphere stops exactly at step N. The energy the
// contact dissipates is the kinetic energy 7/10 m v0^2, to round-off.
TEST_P(RollingSphere, DeceleratesAtTheClosedFormRateAndStopsAtTheClosedFormDistance) {
  const auto [dimension, solver] = GetParam();
  const double mu_r = 0.1, h = 1e-3;
  const double a = 5.0 / 7.0 * mu_r * kG;
  const int N = 200;
  const double v0 = N * h * a;
  auto sim = sphere_on_floor(0.5, mu_r, 0.0, dimension, solver);
  sim.particles().velocity[0] = Vector3d(v0, 0, 0);
  sim.particles().angular_velocity[0] = Vector3d(0, 0, -v0 / kRadius);
  const double x0 = sim.particles().position[0].x();
  const double m = sim.particles().mass[0];
  double dissipated = 0.0, balance = 0.0;
  for (int step = 1; step <= N + 100; ++step) {
    const StepReport report = sim.step(h);
    dissipated += report.contact_dissipation_J;
    balance += report.energy_change_J + report.contact_dissipation_J + report.numerical_dissipation_J;
    const double expected = std::max(v0 - step * h * a, 0.0);
    ASSERT_NEAR(sim.particles().velocity[0].x(), expected, 1e-12 * v0) << "step " << step;
    // Rolling without slip throughout: v = -R w_z.
    ASSERT_NEAR(sim.particles().angular_velocity[0].z() * kRadius, -expected, 1e-12 * v0);
    ASSERT_NEAR(sim.particles().position[0].y(), kRadius, 1e-15);
  }
  EXPECT_NEAR(sim.particles().position[0].x() - x0, v0 * v0 / (2 * a), 1e-10 * v0 * v0 / a);
  EXPECT_LT(sim.max_speed(), 1e-14);
  EXPECT_NEAR(dissipated, 0.7 * m * v0 * v0, 1e-9 * m * v0 * v0);
  EXPECT_NEAR(balance, 0.0, 1e-12 * m * v0 * v0);
}

// On an incline, a sphere at rest stays at rest while tan a <= mu_r (the rolling torque
// m g R sin a it must hold is at most mu_r R m g cos a), and rolls down with
//   a = 5/7 g (sin a - mu_r cos a)
// above it (mu = 0.5 is enough not to slip: it needs 2/7 tan a + 5/7 mu_r <= mu).
TEST_P(RollingSphere, OnAnInclineStaysBelowTheRollingAngleAndRollsAboveIt) {
  const auto [dimension, solver] = GetParam();
  const double mu_r = 0.1, h = 1e-3;
  for (const double ratio : {0.5, 0.99}) {
    auto sim = sphere_on_floor(0.5, mu_r, std::atan(ratio * mu_r), dimension, solver);
    const Vector3d start = sim.particles().position[0];
    for (int step = 0; step < 500; ++step) sim.step(h);
    EXPECT_LT(sim.max_speed(), 1e-13) << "tan a = " << ratio << " mu_r";
    EXPECT_LT(sim.particles().angular_velocity[0].norm() * kRadius, 1e-13);
    EXPECT_LT((sim.particles().position[0] - start).norm(), 1e-14);
  }
  for (const double ratio : {1.01, 2.0}) {
    const double angle = std::atan(ratio * mu_r);
    auto sim = sphere_on_floor(0.5, mu_r, angle, dimension, solver);
    const double a = 5.0 / 7.0 * kG * (std::sin(angle) - mu_r * std::cos(angle));
    const int N = 300;
    for (int step = 0; step < N; ++step) sim.step(h);
    EXPECT_NEAR(sim.particles().velocity[0].x(), N * h * a, 1e-10 * N * h * a)
        << "tan a = " << ratio << " mu_r";
    EXPECT_NEAR(sim.particles().angular_velocity[0].z() * kRadius, -N * h * a, 1e-10 * N * h * a);
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, RollingSphere,
                         ::testing::Values(std::tuple{3, "nlgs"}, std::tuple{2, "nlgs"},
                                           std::tuple{3, "nlgs_coloured"}, std::tuple{3, "apgd"},
                                           std::tuple{2, "apgd"}));

// Between two spheres the lever of the rolling torque is R_eff = R_i R_j / (R_i + R_j). A
// sphere resting on a fixed sphere of the same radius straight below, gravity tilted by a:
// the contact must hold the torque m g R sin a about the upper centre with at most
// mu_r R_eff m g cos a, R_eff = R / 2, so it holds exactly while tan a <= mu_r / 2 (with R_i
// as the lever it would hold up to mu_r).
class RollingOnSphere : public ::testing::TestWithParam<const char*> {};

TEST_P(RollingOnSphere, TwoSpheresUseTheEffectiveRadius) {
  const double mu_r = 0.2;
  for (const double ratio : {0.9, 1.1}) {
    const double angle = std::atan(ratio * mu_r / 2);
    ParticleSet set;
    const double m = sphere_mass(kRadius, kDensity);
    set.add(Vector3d(0, 0, 0), kRadius, m, 0, /*is_fixed=*/true);
    set.add(Vector3d(0, 2 * kRadius, 0), kRadius, m, 0);
    NscdIntegrator sim(std::move(set), {rolling_steel(0.9, mu_r)}, {},
                       Vector3d(kG * std::sin(angle), -kG * std::cos(angle), 0), 3,
                       rolling_tight(GetParam()));
    for (int step = 0; step < 20; ++step) sim.step();
    if (ratio < 1) EXPECT_LT(sim.max_speed(), 1e-13);
    else EXPECT_GT(sim.max_speed(), 1e-5);  // rolls over the lower sphere
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, RollingOnSphere, ::testing::Values("nlgs", "apgd"));

// Without rolling friction (the default) nothing changes: a rolling sphere keeps rolling.
TEST(RollingFriction, ZeroRollsFreely) {
  auto sim = sphere_on_floor(0.5, 0.0, 0.0, 3);
  sim.particles().velocity[0] = Vector3d(0.01, 0, 0);
  sim.particles().angular_velocity[0] = Vector3d(0, 0, -0.01 / kRadius);
  for (int step = 0; step < 100; ++step) sim.step();
  EXPECT_NEAR(sim.particles().velocity[0].x(), 0.01, 1e-15);
}

namespace {

// `count` spheres (radii 1 and 0.7 mm, mu = 0.5, mu_r = 0.1) settled in a 3D box until every
// speed is below 1e-9 m/s, solved to 1e-8 as the 2D rest test does (NscdRest).
NscdIntegrator settled_pile_3d(std::size_t count) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-8;
  NscdIntegrator sim = random_pile(count, 3, 0.5, 5, parameters, 0.1);
  for (int step = 0; step < 5000 && !(step > 10 && sim.max_speed() < 1e-9); ++step) sim.step();
  EXPECT_LT(sim.max_speed(), 1e-9) << "the pile did not settle within 5 s";
  return sim;
}

}  // namespace

// A 3D pile with rolling resistance, once settled, stays exactly where it is for 10,000 steps
// (the 2D rest test of NscdRest, in 3D): no speed above 1e-8 m/s, nothing moves 1e-9 m. The
// Without rolling resistance the same pile never comes to rest: with mu_r = 0 it was still
// at 1.3e-3 m/s after 5 s and moved 8 mm in the 10,000 steps (spheres rolling freely on the
// floor between the others: rolling without slip dissipates nothing).
TEST(RollingFriction, SettledPile3DStaysAtRest) {
  auto sim = settled_pile_3d(30);
  const Drift drift = drift_over(sim, 10000);
  EXPECT_LT(drift.fastest_m_per_s, 1e-8);
  EXPECT_LT(drift.moved_m, 1e-9);
}

namespace {

struct RollingSolve {
  std::vector<Vector3d> r, m, v, w;
  SolveReport report;
};

RollingSolve solve_rolling_cold(ContactSolver& solver, const ContactProblem& problem) {
  RollingSolve out;
  out.r.assign(problem.size(), Vector3d::Zero());
  out.m.assign(problem.size(), Vector3d::Zero());
  out.report = solver.solve_with_rolling(problem, out.r, out.m, out.v, out.w);
  return out;
}


}  // namespace

// The settled 3D pile's last contact problem, solved cold with rolling resistance by nlgs,
// nlgs_coloured and apgd (the latter two at 1 and 2 threads). A frictional pile is statically
// indeterminate, so the reactions themselves are not unique; what is: all leave the pile at
// rest (the velocities the reactions give agree within the tolerance's share of g h), all
// reach the natural-map residual of the tolerance with the rolling blocks counted
// (NaturalMapResidual.h), and every reaction obeys its laws: |r_t| <= mu r_n,
// |m| <= mu_r R_eff r_n with m perpendicular to n. The parallel solvers give the same bits at
// 1 and 2 threads.
TEST(RollingFriction, EverySolverMatchesGaussSeidelWithSameBitsForAnyThreadCount) {
  auto sim = settled_pile_3d(30);
  sim.step();
  const ContactProblem& problem = sim.problem();
  ASSERT_TRUE(problem.rolling);
  constexpr double tolerance = 1e-7;
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.max_iterations = 100000;
  settings.stall_sweeps = 100000;
  GaussSeidelSolver nlgs(settings);
  const RollingSolve reference = solve_rolling_cold(nlgs, problem);
  ASSERT_TRUE(reference.report.converged);
  auto at_threads = [&](const char* name, int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    // Parallel at any size.
    SolverSettings parallel = settings;
    parallel.parallel_from = 0;
    std::unique_ptr<ContactSolver> solver;
    if (std::string(name) == "apgd") solver = std::make_unique<ApgdSolver>(parallel);
    else solver = std::make_unique<ColouredGaussSeidelSolver>(parallel);
    RollingSolve out = solve_rolling_cold(*solver, problem);
    omp_set_num_threads(before);
    return out;
  };
  double carried = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) carried = std::max(carried, reference.m[c].norm());
  EXPECT_GT(carried, 0.0);  // the pile leans on its rolling torques
  const double gh = kG * sim.parameters().time_step;
  for (const char* name : {"nlgs_coloured", "apgd"}) {
    SCOPED_TRACE(name);
    const RollingSolve two = at_threads(name, 2), one = at_threads(name, 1);
    ASSERT_TRUE(two.report.converged) << two.report.residual << " after " << two.report.sweeps;
    EXPECT_EQ(one.report.sweeps, two.report.sweeps);
    EXPECT_TRUE(same_bits(one.r, two.r));
    EXPECT_TRUE(same_bits(one.m, two.m));
    EXPECT_TRUE(same_bits(one.w, two.w));
    for (std::size_t i = 0; i < problem.particle_count; ++i) {
      EXPECT_LT((reference.v[i] - two.v[i]).norm(), 1e-5 * gh) << "particle " << i;
      EXPECT_LT(reference.v[i].norm(), 1e-5 * gh) << "particle " << i;
    }
    for (const RollingSolve* s : {&reference, &two}) {
      EXPECT_LE(natural_map_residual(problem, s->r, s->m, s->v, s->w), 2.0 * tolerance);
      for (std::size_t c = 0; c < problem.size(); ++c) {
        const Vector3d& r = s->r[c];
        EXPECT_LE(std::hypot(r[1], r[2]), problem.mu[c] * r[0] * (1 + 1e-12) + 1e-300);
        EXPECT_LE(s->m[c].norm(), problem.rolling_limit[c] * r[0] * (1 + 1e-12) + 1e-300);
        EXPECT_LE(std::abs(s->m[c].dot(problem.normal[c])), 1e-12 * s->m[c].norm());
      }
    }
  }
}
