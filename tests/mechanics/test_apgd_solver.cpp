// The accelerated solver ("apgd") against closed-form statics, against Gauss-Seidel on a
// settled frictional pile, and its determinism under OpenMP.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <string>

#include "MechanicsTestScenes.h"
#include "mechanics/ApgdSolver.h"
#include "mechanics/ContactSolverRegistry.h"
#include "mechanics/NaturalMapResidual.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

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

// A 3D frictional pile at rest: side x side x layers touching spheres on a simple cubic
// lattice on a floor (mu = 0.3), after one step. Statics: in each column the contact under
// the sphere of layer k carries (layers - k) m g h; side contacts carry nothing.
constexpr int kSide = 5, kLayers = 6;
const NscdIntegrator& lattice_pile() {
  static const NscdIntegrator sim = [] {
    ParticleSet set;
    const double m = sphere_mass(test::kRadius, test::kDensity), d = 2.0 * test::kRadius;
    for (int y = 0; y < kLayers; ++y)
      for (int z = 0; z < kSide; ++z)
        for (int x = 0; x < kSide; ++x)
          set.add(Vector3d(test::kRadius + x * d, test::kRadius + y * d, test::kRadius + z * d),
                  test::kRadius, m, 0);
    NscdIntegrator s(std::move(set), {test::steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -test::kG, 0), 3, NscdParameters{});
    s.step();
    return s;
  }();
  return sim;
}

struct Solved {
  std::vector<Vector3d> r, v, w;
  SolveReport report;
};

SolverSettings tight(double tolerance) {
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.max_iterations = 200000;
  return settings;
}

Solved solve_cold(const ContactProblem& problem, ContactSolver& solver) {
  Solved out;
  out.r.assign(problem.size(), Vector3d::Zero());
  out.report = solver.solve(problem, out.r, out.v, out.w);
  return out;
}

Solved solve_cold(const ContactProblem& problem, const std::string& name, double tolerance) {
  return solve_cold(problem, *make_contact_solver(name, tight(tolerance)));
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
  const NscdIntegrator& sim = lattice_pile();
  const ContactProblem& problem = sim.problem();
  ASSERT_GT(problem.size(), 300u);
  const double tolerance = 1e-8;
  const Solved gs = solve_cold(problem, "nlgs", tolerance);
  const Solved ap = solve_cold(problem, "apgd", tolerance);
  ASSERT_TRUE(gs.report.converged) << gs.report.residual;
  ASSERT_TRUE(ap.report.converged) << ap.report.residual << " after " << ap.report.sweeps;
  EXPECT_LE(natural_map_residual(problem, ap.r, ap.v, ap.w), tolerance);
  const double m = sphere_mass(test::kRadius, test::kDensity);
  const double h = sim.parameters().time_step, weight = m * test::kG * h;  // N s
  double difference = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    difference = std::max(difference, (gs.r[c] - ap.r[c]).norm());
    // Statics: a vertical contact under sphere i carries the spheres above i and i itself.
    const bool vertical = std::abs(problem.normal[c].y()) > 0.5;
    const double y = sim.particles().position[problem.body_i[c]].y();
    const int layer = static_cast<int>(std::lround((y - test::kRadius) / (2.0 * test::kRadius)));
    const bool on_floor = problem.body_j[c] < 0;
    const double expected = !vertical ? 0.0 : (kLayers - layer - (on_floor ? 0 : 1)) * weight;
    EXPECT_NEAR(ap.r[c][0], expected, 1e-6 * kLayers * weight) << "contact " << c;
    EXPECT_NEAR(ap.r[c].tail<2>().norm(), 0.0, 1e-6 * kLayers * weight) << "contact " << c;
  }
  EXPECT_LE(difference, 1e-6 * kLayers * weight);
}

TEST(ApgdSolver, SameThreadCountGivesBitwiseIdenticalReactions) {
  const ContactProblem& problem = lattice_pile().problem();
  // A fresh solver each time: a solver keeps its step-size estimate between solves.
  auto run = [&] {
    ApgdSolver solver(tight(1e-8), 0);  // parallel at any size
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
  double largest = 0.0, difference = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    largest = std::max(largest, serial.r[c].norm());
    difference = std::max(difference, (serial.r[c] - first.r[c]).norm());
  }
  ASSERT_GT(largest, 0.0);
  EXPECT_LE(difference, 1e-8 * largest);
}
