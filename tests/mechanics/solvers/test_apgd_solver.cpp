// The accelerated solver ("apgd") against closed-form statics, against Gauss-Seidel on a
// settled frictional pile, and its determinism under OpenMP.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <string>

#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/ApgdSolver.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;
using test::lattice_pile;
using test::Solved;
using test::solve_cold;
using test::tight;

namespace {

// A column of `count` equal spheres (mass m, radius R) standing on a floor, at rest and
// touching: one step h under gravity g. Contact 0 is the floor, contact k (k >= 1) is sphere
// k-1 (i, below) under sphere k (j); the normal points from j to i, i.e. down.
ContactProblem column_problem(int count, double m, double h, double g, double mu) {
  ContactProblem p;
  p.dimension = 3;
  p.inverse_mass.assign(count, 1.0 / m);
  const double radius = 1e-3, inertia = 0.4 * m * radius * radius;
  p.inverse_inertia.assign(count, 1.0 / inertia);
  p.free_velocity.assign(count, Vector3d(0, -g * h, 0));
  p.free_angular_velocity.assign(count, Vector3d::Zero());
  p.resize_contacts(count);
  for (int k = 0; k < count; ++k) {
    const bool floor = k == 0;
    p.body_i[k] = floor ? 0 : k - 1;
    p.body_j[k] = floor ? -1 : k;
    p.normal[k] = floor ? Vector3d(0, 1, 0) : Vector3d(0, -1, 0);
    p.tangent1[k] = Vector3d(1, 0, 0);
    p.tangent2[k] = p.normal[k].cross(p.tangent1[k]);
    p.lever_i[k] = radius;
    p.lever_j[k] = floor ? 0.0 : radius;
    const int bodies = floor ? 1 : 2;
    p.w_n[k] = bodies / m;
    p.w_t[k] = bodies * (1.0 / m + radius * radius / inertia);
    p.bias[k] = 0.0;
    p.mu[k] = mu;
  }
  p.add_fixed_wall_bodies(1);  // the floor
  return p;
}

}  // namespace

TEST(ApgdSolver, UnknownSolverNameListsNlgsAndApgd) {
  try {
    make_contact_solver("pgs", {});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"nlgs\""), std::string::npos) << what;
    EXPECT_NE(what.find("\"apgd\""), std::string::npos) << what;
  }
}

TEST(ApgdSolver, FrictionlessColumnCarriesTheWeightAbove) {
  // Statics: contact k carries the weight of the N - k spheres above it, (N - k) m g h.
  const int count = 10;
  const double m = 3.3e-5, h = 1e-3, g = 9.81;
  const ContactProblem problem = column_problem(count, m, h, g, 0.0);
  const Solved s = solve_cold(problem, "apgd", 1e-10);
  EXPECT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
  for (int k = 0; k < count; ++k) {
    const double expected = (count - k) * m * g * h;
    EXPECT_NEAR(s.r[k][0], expected, 1e-8 * count * m * g * h) << "contact " << k;
    EXPECT_EQ(s.r[k][1], 0.0);
    EXPECT_EQ(s.r[k][2], 0.0);
  }
  for (int b = 0; b < count; ++b) EXPECT_LT(s.v[b].norm(), 1e-7 * g * h) << "sphere " << b;
  EXPECT_LE(natural_map_residual(problem, s.r, s.v, s.w), 1e-10);
  // Warm-started from its answer, it stops at once.
  std::vector<Vector3d> r = s.r, v, w;
  const SolveReport warm = make_contact_solver("apgd", {})->solve(problem, r, v, w);
  EXPECT_TRUE(warm.converged);
  EXPECT_EQ(warm.sweeps, 0);
}

TEST(ApgdSolver, FrictionalPileAtRestMatchesGaussSeidelAndStatics) {
  // Statics hold exactly; the solvers agree to the tolerance.
  const double tolerance = 1e-8;
  test::expect_pile_solved_like_gauss_seidel("apgd", tolerance, tolerance);
}

TEST(ApgdSolver, SameThreadCountGivesBitwiseIdenticalReactions) {
  const ContactProblem& problem = lattice_pile().problem();
  // A fresh solver each time: a solver keeps its step-size estimate between solves.
  auto run = [&] {
    SolverSettings settings = tight(1e-8);
    settings.parallel_from = 0;  // parallel at any size
    ApgdSolver solver(settings);
    return solve_cold(problem, solver);
  };
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
  const Solved first = run();
  const Solved second = run();
  omp_set_num_threads(1);
  const Solved serial = run();
  omp_set_num_threads(threads);
  ASSERT_TRUE(first.report.converged);
  ASSERT_EQ(first.r.size(), second.r.size());
  EXPECT_EQ(first.report.sweeps, second.report.sweeps);
  EXPECT_EQ(0, std::memcmp(first.r.data(), second.r.data(), first.r.size() * sizeof(Vector3d)));
  EXPECT_EQ(0, std::memcmp(first.v.data(), second.v.data(), first.v.size() * sizeof(Vector3d)));
  // 1 and 2 threads: the reductions sum fixed blocks in a fixed order, so they agree too
  // (asserted within the tolerance, the contract; bitwise in practice).
  test::expect_close_reactions(serial.r, first.r, 1e-8);
}
