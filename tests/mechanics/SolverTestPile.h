#pragma once
// The settled frictional pile the contact-solver tests share ("nlgs", "apgd",
// "nlgs_coloured"), its closed-form statics, and cold solves.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "MechanicsTestScenes.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"

namespace tmdem::mechanics::test {

// A 3D frictional pile at rest: kPileSide x kPileSide x kPileLayers touching spheres on a
// simple cubic lattice on a floor (mu = 0.3), after one step. Statics: in each column the
// contact under the sphere of layer k carries (layers - k) m g h; side contacts carry nothing.
inline constexpr int kPileSide = 5, kPileLayers = 6;
inline const NscdIntegrator& lattice_pile() {
  static const NscdIntegrator sim = [] {
    ParticleSet set;
    const double m = sphere_mass(kRadius, kDensity), d = 2.0 * kRadius;
    for (int y = 0; y < kPileLayers; ++y)
      for (int z = 0; z < kPileSide; ++z)
        for (int x = 0; x < kPileSide; ++x)
          set.add(Eigen::Vector3d(kRadius + x * d, kRadius + y * d, kRadius + z * d), kRadius, m, 0);
    NscdIntegrator s(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Eigen::Vector3d(0, -kG, 0), 3, nlgs_parameters());
    s.step();
    return s;
  }();
  return sim;
}

// Weight of one sphere of the pile over one step, N s.
inline double pile_weight_impulse() {
  return sphere_mass(kRadius, kDensity) * kG * lattice_pile().parameters().time_step;
}

// Checks reactions r of the pile's problem against the statics, to `tolerance` N s.
inline void expect_pile_statics(const std::vector<Eigen::Vector3d>& r, double tolerance) {
  const NscdIntegrator& sim = lattice_pile();
  const ContactProblem& problem = sim.problem();
  const double weight = pile_weight_impulse();
  for (std::size_t c = 0; c < problem.size(); ++c) {
    // A vertical contact under sphere i carries the spheres above i and i itself.
    const bool vertical = std::abs(problem.normal[c].y()) > 0.5;
    const double y = sim.particles().position[problem.body_i[c]].y();
    const int layer = static_cast<int>(std::lround((y - kRadius) / (2.0 * kRadius)));
    const bool on_floor = problem.body_j[c] < 0;
    const double expected = !vertical ? 0.0 : (kPileLayers - layer - (on_floor ? 0 : 1)) * weight;
    EXPECT_NEAR(r[c][0], expected, tolerance) << "contact " << c;
    EXPECT_NEAR(r[c].tail<2>().norm(), 0.0, tolerance) << "contact " << c;
  }
}

// Largest |a_c - b_c| over the contacts.
inline double largest_difference(const std::vector<Eigen::Vector3d>& a,
                                 const std::vector<Eigen::Vector3d>& b) {
  double difference = 0.0;
  for (std::size_t c = 0; c < a.size(); ++c) difference = std::max(difference, (a[c] - b[c]).norm());
  return difference;
}

inline SolverSettings tight(double tolerance) {
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.max_iterations = 200000;
  return settings;
}

struct Solved {
  std::vector<Eigen::Vector3d> r, v, w;
  SolveReport report;
};

inline Solved solve_cold(const ContactProblem& problem, ContactSolver& solver) {
  Solved out;
  out.r.assign(problem.size(), Eigen::Vector3d::Zero());
  out.report = solver.solve(problem, out.r, out.v, out.w);
  return out;
}

inline Solved solve_cold(const ContactProblem& problem, const std::string& name, double tolerance) {
  return solve_cold(problem, *make_contact_solver(name, tight(tolerance)));
}

// Solver `name` and "nlgs", cold at `tolerance`, on the pile: both converge, `name`'s answer
// meets the common residual within residual_bound, the statics, and "nlgs"'s reactions.
inline void expect_pile_solved_like_gauss_seidel(const std::string& name, double tolerance,
                                                 double residual_bound) {
  const ContactProblem& problem = lattice_pile().problem();
  ASSERT_GT(problem.size(), 300u);
  const Solved gs = solve_cold(problem, "nlgs", tolerance);
  const Solved other = solve_cold(problem, name, tolerance);
  ASSERT_TRUE(gs.report.converged) << gs.report.residual;
  ASSERT_TRUE(other.report.converged) << other.report.residual << " after " << other.report.sweeps;
  EXPECT_LE(natural_map_residual(problem, other.r, other.v, other.w), residual_bound);
  const double weight = pile_weight_impulse();
  expect_pile_statics(other.r, 1e-6 * kPileLayers * weight);
  EXPECT_LE(largest_difference(gs.r, other.r), 1e-6 * kPileLayers * weight);
}

// a and b agree to `relative` times the largest |a_c| (which must be positive).
inline void expect_close_reactions(const std::vector<Eigen::Vector3d>& a,
                                   const std::vector<Eigen::Vector3d>& b, double relative) {
  double largest = 0.0;
  for (const Eigen::Vector3d& r : a) largest = std::max(largest, r.norm());
  ASSERT_GT(largest, 0.0);
  EXPECT_LE(largest_difference(a, b), relative * largest);
}

// The disk pile of NscdRest.RestingPileStaysAtRestFor10000Steps (settled with "nlgs"), carried
// on with solver `name` (a new integrator: its first steps start cold, so 200 steps first),
// then stepped 10,000 times: how far it moved and how fast. `sim` receives the integrator.
inline Drift drift_at_rest_with(const std::string& name, std::unique_ptr<NscdIntegrator>& sim) {
  const NscdIntegrator settled = settled_disk_pile();
  EXPECT_LT(settled.max_speed(), 1e-9) << "the pile did not settle within 5 s";
  NscdParameters parameters = settled.parameters();
  parameters.solver = name;
  sim = std::make_unique<NscdIntegrator>(settled.particles(), settled.materials(), settled.walls(),
                                         Eigen::Vector3d(0, -kG, 0), 2, parameters);
  for (int step = 0; step < 200; ++step) sim->step();
  return drift_over(*sim, 10000);
}

// A 3D pile with rolling resistance (30 spheres, radii 1 and 0.7 mm, mu = 0.5, mu_r = 0.1)
// settled with "nlgs" at tolerance 1e-8, then one more step: its problem is the one solved.
inline NscdIntegrator settled_rolling_pile() {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-8;
  NscdIntegrator sim = random_pile(30, 3, 0.5, 5, parameters, 0.1);
  for (int step = 0; step < 5000 && !(step > 10 && sim.max_speed() < 1e-9); ++step) sim.step();
  EXPECT_LT(sim.max_speed(), 1e-9);
  sim.step();
  return sim;
}

// The rolling pile's problem solved cold by `solver` at `tolerance`: converged, the natural-map
// residual of the tolerance with the rolling blocks counted, every reaction within both cones,
// the rolling torques taking part, and the pile left at rest as "nlgs" leaves it.
inline void expect_rolling_pile_solved(const NscdIntegrator& sim, ContactSolver& solver, double tolerance) {
  const ContactProblem& problem = sim.problem();
  ASSERT_TRUE(problem.rolling);
  std::vector<Eigen::Vector3d> r(problem.size(), Eigen::Vector3d::Zero()), m = r, v, w;
  const SolveReport report = solver.solve_with_rolling(problem, r, m, v, w);
  ASSERT_TRUE(report.converged) << report.residual << " after " << report.sweeps;
  EXPECT_LE(natural_map_residual(problem, r, m, v, w), 2.0 * tolerance);
  const double gh = kG * sim.parameters().time_step;
  for (std::size_t i = 0; i < problem.particle_count; ++i) EXPECT_LT(v[i].norm(), 1e-5 * gh) << "particle " << i;
  double carried = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    EXPECT_LE(std::hypot(r[c][1], r[c][2]), problem.mu[c] * r[c][0] * (1 + 1e-12) + 1e-300);
    EXPECT_LE(m[c].norm(), problem.rolling_limit[c] * r[c][0] * (1 + 1e-12) + 1e-300);
    carried = std::max(carried, m[c].norm());
  }
  EXPECT_GT(carried, 0.0);  // the rolling torques take part
}

}  // namespace tmdem::mechanics::test
