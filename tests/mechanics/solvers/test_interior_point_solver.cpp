// "ipm" (InteriorPointSolver.h) and its cone algebra (SecondOrderCone.h): the Nesterov-Todd
// scaling's defining identities, the step to the boundary against its closed form; then the
// solver against the closed-form statics of heavy-on-light columns (the depth and mass ratio
// that make Gauss-Seidel crawl), the frictional lattice pile's statics and "nlgs"'s reactions,
// the rolling pile, and Siconos' residual of the tolerance on each.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mechanics/ColumnStatics.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/solvers/InteriorPointSolver.h"
#include "mechanics/solvers/SecondOrderCone.h"
#include "mechanics/solvers/SerialBlas.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace ipm_test {

double siconos_of(const ContactProblem& problem, const Solved& s) {
  return siconos_residual(problem, s.r, {}, s.v, s.w, free_velocity_norm(problem));
}

}  // namespace ipm_test

// W s = W^-1 z = lambda, W symmetric, for interior pairs of every dimension.
TEST(SecondOrderCone, NesterovToddScalingMapsSToZ) {
  const Eigen::Vector3d s(2.0, 0.5, -0.3), z(1.5, -0.2, 1.1);
  for (int dim = 1; dim <= 3; ++dim) {
    SCOPED_TRACE(dim);
    Eigen::Vector3d sd = s, zd = z;
    for (int k = dim; k < 3; ++k) sd[k] = zd[k] = 0.0;
    const cone::Scaling w = cone::nesterov_todd(dim, sd, zd);
    EXPECT_LE((w.w * w.w * sd - zd).norm(), 1e-14);
    EXPECT_LE((w.w * sd - w.w_inverse * zd).norm(), 1e-14);
    EXPECT_LE(((w.w * w.w_inverse).topLeftCorner(dim, dim) - Eigen::MatrixXd::Identity(dim, dim)).norm(), 1e-14);
    EXPECT_LE((w.w - w.w.transpose()).norm(), 0.0);
    // lambda o (lambda \ a) = a.
    const Eigen::Vector3d a(0.3, -0.7, 0.2);
    Eigen::Vector3d ad = a;
    for (int k = dim; k < 3; ++k) ad[k] = 0.0;
    EXPECT_LE((cone::jordan_product(dim, w.lambda, cone::jordan_divide(dim, w.lambda, ad)) - ad).norm(), 1e-14);
  }
}

// From (1, 0, 0) along (-1, 1, 0) the cone's edge x_0 = |x_1| is met at alpha = 1/2; along
// (0, 1, 0) at alpha = 1; along (1, 0, 0) never.
TEST(SecondOrderCone, StepToBoundary) {
  const Eigen::Vector3d x(1.0, 0.0, 0.0);
  EXPECT_NEAR(cone::step_to_boundary(3, x, Eigen::Vector3d(-1.0, 1.0, 0.0)), 0.5, 1e-15);
  EXPECT_NEAR(cone::step_to_boundary(3, x, Eigen::Vector3d(0.0, 1.0, 0.0)), 1.0, 1e-15);
  EXPECT_TRUE(std::isinf(cone::step_to_boundary(3, x, Eigen::Vector3d(1.0, 0.0, 0.0))));
  EXPECT_NEAR(cone::step_to_boundary(1, x, Eigen::Vector3d(-4.0, 0.0, 0.0)), 0.25, 1e-15);
  EXPECT_NEAR(cone::step_to_boundary(2, x, Eigen::Vector3d(-1.0, 1.0, 0.0)), 0.5, 1e-15);
  // Straight through the apex (a double root of J): stopped at the apex, not let into -Q.
  const Eigen::Vector3d axis(5.016e-4, 0.0, 0.0);
  EXPECT_NEAR(cone::step_to_boundary(3, axis, Eigen::Vector3d(-7.842e-3, 0.0, 0.0)), 5.016e-4 / 7.842e-3, 1e-9);
}

// A column of ten spheres alternating 1 g and 1 kg (Gauss-Seidel contracts by 0.9995 per sweep
// on it): every contact carries the weight above it to 1e-9, in a few tens of iterations.
TEST(InteriorPoint, HeavyOnLightColumnCarriesTheWeightsAbove) {
  std::vector<double> masses;
  for (int k = 0; k < 5; ++k) masses.insert(masses.end(), {1e-3, 1.0});
  const NscdIntegrator sim = column(masses);
  InteriorPointSolver solver(tight(1e-10));
  const Solved s = solve_cold(sim.problem(), solver);
  ASSERT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
  EXPECT_LE(ipm_test::siconos_of(sim.problem(), s), 1e-10);
  expect_column_statics(sim, s.r, 1e-9);
  EXPECT_LE(s.report.sweeps, 60);
}

// The iterations do not grow with depth: 10 and 160 spheres alike.
TEST(InteriorPoint, IterationsFlatInDepth) {
  int iterations[2];
  for (int k = 0; k < 2; ++k) {
    const std::vector<double> masses(k == 0 ? 10 : 160, 1e-2);
    const NscdIntegrator sim = column(masses);
    InteriorPointSolver solver(tight(1e-10));
    const Solved s = solve_cold(sim.problem(), solver);
    ASSERT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
    expect_column_statics(sim, s.r, 1e-7);
    iterations[k] = s.report.sweeps;
  }
  EXPECT_LE(iterations[1], 2 * iterations[0]) << iterations[0] << " then " << iterations[1];
}

// The frictional 5 x 5 x 6 lattice pile: Siconos' residual of the tolerance, the statics and
// "nlgs"'s reactions to 1e-6 of the weights.
TEST(InteriorPoint, FrictionalLatticePileMatchesGaussSeidelAndStatics) {
  const ContactProblem& problem = lattice_pile().problem();
  InteriorPointSolver solver(tight(1e-10));
  const Solved s = solve_cold(problem, solver);
  ASSERT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
  EXPECT_LE(ipm_test::siconos_of(problem, s), 1e-10);
  const double weight = pile_weight_impulse();
  expect_pile_statics(s.r, 1e-6 * kPileLayers * weight);
  const Solved gs = solve_cold(problem, "nlgs", 1e-10);
  EXPECT_LE(largest_difference(gs.r, s.r), 1e-6 * kPileLayers * weight);
}

// With rolling resistance: both cones held, the pile left at rest, the rolling torques used.
TEST(InteriorPoint, RollingPileLikeGaussSeidel) {
  const NscdIntegrator sim = settled_rolling_pile();
  InteriorPointSolver solver(tight(1e-9));
  expect_rolling_pile_solved(sim, solver, 1e-7);
}

// Open candidates far from closing (the look-ahead's, at gap / h = 1.5 m/s here, ten for each
// contact of the lattice pile) inflate ||q|| 400-fold, and Siconos' residual relative to it no
// longer sees reactions left on them: an interior iterate has every reaction strictly inside
// its cone, and "ipm" without the crossover that ends it (Options::crossover) stops after 4
// iterations with spheres driven at 10.8 m/s. With them (the crossover) the candidates carry
// exactly nothing, the pile is at rest (within a hundredth of h g = 9.8e-3 m/s) and carries its
// weights.
TEST(InteriorPoint, OpenCandidatesCarryNothingWhateverTheirGaps) {
  const ContactProblem& pile = lattice_pile().problem();
  const std::size_t contacts = pile.size(), copies = 10;
  ContactProblem problem = pile;
  problem.resize_contacts(contacts * (1 + copies));
  for (std::size_t k = 0; k < copies; ++k) {
    for (std::size_t c = 0; c < contacts; ++c) {
      const std::size_t slot = contacts * (1 + k) + c;
      problem.copy_contact(slot, pile, c);
      problem.bias[slot] = 1.5;
    }
  }
  ASSERT_GT(free_velocity_norm(problem), 300.0 * free_velocity_norm(pile));
  auto largest_speed = [](const Solved& s) {
    double v = 0.0;
    for (std::size_t i = 0; i < kPileSide * kPileSide * kPileLayers; ++i) v = std::max(v, s.v[i].norm());
    return v;
  };
  const double weight = pile_weight_impulse();
  const double weight_speed = kG * lattice_pile().parameters().time_step;  // m/s, h g
  {
    InteriorPointSolver::Options bare;
    bare.crossover = false;
    InteriorPointSolver solver(tight(1e-4), bare);
    const Solved s = solve_cold(problem, solver);
    ASSERT_TRUE(s.report.converged);
    EXPECT_GT(largest_speed(s), weight_speed) << "the interior point alone no longer leaves the open candidates loaded";
  }
  InteriorPointSolver solver(tight(1e-4));
  const Solved s = solve_cold(problem, solver);
  ASSERT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
  EXPECT_LE(ipm_test::siconos_of(problem, s), 1e-4);
  for (std::size_t c = contacts; c < problem.size(); ++c) EXPECT_EQ(s.r[c], Eigen::Vector3d::Zero()) << "candidate " << c;
  EXPECT_LE(largest_speed(s), 1e-2 * weight_speed);
  std::vector<Eigen::Vector3d> loaded(s.r.begin(), s.r.begin() + std::ptrdiff_t(contacts));
  expect_pile_statics(loaded, 1e-3 * kPileLayers * weight);
}

// "nncg_ipm" (FallbackContactSolver.h): where nncg converges, nncg's reactions to the bit; where
// it does not (here: 20 sweeps on the heavy-on-light column), the interior point's, which carry
// the weights above each contact.
TEST(InteriorPoint, NncgIpmIsNncgWhereNncgConvergesAndIpmWhereItDoesNot) {
  std::vector<double> masses;
  for (int k = 0; k < 5; ++k) masses.insert(masses.end(), {1e-3, 1.0});
  const NscdIntegrator sim = column(masses);
  const ContactProblem& problem = sim.problem();
  {
    auto plain = make_contact_solver("nncg", tight(1e-8));
    auto hybrid = make_contact_solver("nncg_ipm", tight(1e-8));
    const Solved a = solve_cold(problem, *plain), b = solve_cold(problem, *hybrid);
    ASSERT_TRUE(a.report.converged);
    EXPECT_EQ(a.report.sweeps, b.report.sweeps);
    for (std::size_t c = 0; c < problem.size(); ++c) EXPECT_EQ(a.r[c], b.r[c]) << "contact " << c;
  }
  SolverSettings short_of_sweeps = tight(1e-8);
  short_of_sweeps.max_iterations = 20;
  auto plain = make_contact_solver("nncg", short_of_sweeps);
  ASSERT_FALSE(solve_cold(problem, *plain).report.converged);
  auto hybrid = make_contact_solver("nncg_ipm", short_of_sweeps);
  const Solved s = solve_cold(problem, *hybrid);
  ASSERT_TRUE(s.report.converged) << s.report.residual;
  EXPECT_LE(ipm_test::siconos_of(problem, s), 1e-8);
  expect_column_statics(sim, s.r, 1e-6);
}

// SerialBlas.h: while one is alive the BLAS runs on one thread, and after it on as many as
// before.
TEST(SerialBlas, HoldsTheBlasToOneThreadAndGivesItBack) {
  const int before = SerialBlas::threads();
  if (before == 0) GTEST_SKIP() << "the BLAS is not OpenBLAS: its threads are left as they are";
  SerialBlas::set_threads(2);
  {
    const SerialBlas serial;
    EXPECT_EQ(SerialBlas::threads(), 1);
  }
  EXPECT_EQ(SerialBlas::threads(), 2);
  SerialBlas::set_threads(before);
}

// The interior point gives the same bits whatever the BLAS's threads (OpenBLAS takes them from
// OMP_NUM_THREADS; CHOLMOD's supernodal blocks rounded differently on 2 than on 1, and a 2D
// deposit's settle took another trajectory on 2 threads). A 2D pile of 1,500 disks after 60
// steps of its fall, solved cold by "ipm" for 12 iterations with OpenBLAS on 2 threads and on 1.
TEST(InteriorPoint, SameBitsWhateverTheBlasThreads) {
  const int before = SerialBlas::threads();
  if (before == 0) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  constexpr double width = 0.06, height = 0.2;
  const auto placed = place_random(1500, Eigen::Vector3d::Zero(), Eigen::Vector3d(width, height, 0.0),
                                   {kRadius, 0.7 * kRadius}, {0.5, 0.5}, 3, 2);
  ParticleSet set;
  for (std::size_t i = 0; i < placed.positions.size(); ++i)
    set.add(placed.positions[i], placed.radii[i], sphere_mass(placed.radii[i], kDensity), 0);
  NscdIntegrator sim(std::move(set), {steel(0.5)}, box_walls(width, width, 2), Eigen::Vector3d(0, -kG, 0), 2,
                     nlgs_parameters());
  for (int step = 0; step < 60; ++step) sim.step();
  ASSERT_GT(sim.problem().size(), 3000u);
  SolverSettings settings = tight(1e-12);
  settings.max_iterations = 12;
  Solved solved[2];
  for (int k = 0; k < 2; ++k) {
    SerialBlas::set_threads(k == 0 ? 2 : 1);
    InteriorPointSolver solver(settings);
    solved[k] = solve_cold(sim.problem(), solver);
  }
  SerialBlas::set_threads(before);
  EXPECT_EQ(solved[0].report.sweeps, solved[1].report.sweeps);
  std::size_t differ = 0, loaded = 0;
  for (std::size_t c = 0; c < solved[0].r.size(); ++c) {
    if (solved[1].r[c][0] > 0.0) ++loaded;
    for (int k = 0; k < 3; ++k) differ += solved[0].r[c][k] != solved[1].r[c][k] ? 1 : 0;
  }
  EXPECT_GT(loaded, 1000u);
  EXPECT_EQ(differ, 0u);
}
