// The graph-coloured Gauss-Seidel ("nlgs_coloured"): a proper colouring, recomputed only when
// the contact list changes; the same reactions as "nlgs" and as the closed-form statics on a
// settled frictional pile; bitwise identical results for any thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <set>

#include "mechanics/SameBits.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/ColouredGaussSeidelSolver.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"

using namespace tmdem::mechanics;
using tmdem::mechanics::test::nlgs_parameters;
using Eigen::Vector3d;

namespace {

using tmdem::mechanics::test::same_bits;


}  // namespace

TEST(ColouredGaussSeidel, IsRegisteredByName) {
  const auto& names = contact_solver_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "nlgs_coloured"), names.end());
  EXPECT_EQ(make_contact_solver("nlgs_coloured", {})->name(), "nlgs_coloured");
}

TEST(ColouredGaussSeidel, ColoursAreProperAndRecomputedOnlyWhenTheListChanges) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-4;
  parameters.max_iterations = 300;
  NscdIntegrator sim = test::random_pile(150, 3, 0.3, 3, parameters);
  for (int s = 0; s < 40; ++s) sim.step();
  const ContactProblem& problem = sim.problem();
  ContactColouring colouring;
  ASSERT_TRUE(colouring.update(problem));
  ASSERT_GT(problem.size(), 200u);
  // Every contact exactly once, increasing inside a colour, no particle twice in a colour.
  std::vector<int> seen(problem.size(), 0);
  std::map<std::int32_t, int> contacts_of_body;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    ++contacts_of_body[problem.body_i[c]];
    if (problem.body_j[c] >= 0) ++contacts_of_body[problem.body_j[c]];
  }
  int largest = 0;
  for (const auto& [body, n] : contacts_of_body) largest = std::max(largest, n);
  EXPECT_LE(colouring.colour_count(), static_cast<std::size_t>(2 * largest - 1));
  for (std::size_t k = 0; k < colouring.colour_count(); ++k) {
    std::set<std::int32_t> bodies;
    for (std::int32_t p = colouring.start()[k]; p < colouring.start()[k + 1]; ++p) {
      const std::int32_t c = colouring.order()[p];
      ++seen[c];
      if (p > colouring.start()[k]) {
        EXPECT_LT(colouring.order()[p - 1], c);
      }
      EXPECT_TRUE(bodies.insert(problem.body_i[c]).second) << "colour " << k;
      if (problem.body_j[c] >= 0) {
        EXPECT_TRUE(bodies.insert(problem.body_j[c]).second) << "colour " << k;
      }
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(problem.size()));
  // Same list: kept. A changed list (one contact fewer): coloured again.
  EXPECT_FALSE(colouring.update(problem));
  EXPECT_EQ(colouring.recolourings(), 1u);
  ContactProblem fewer = problem;
  fewer.body_i.pop_back();
  fewer.body_j.pop_back();
  EXPECT_TRUE(colouring.update(fewer));
  EXPECT_EQ(colouring.recolourings(), 2u);
}

// Contacts with one fixed wall may share a colour; contacts with one piston may not (the
// piston's velocity is written by each of them).
TEST(ColouredGaussSeidel, APistonIsABodyAFixedWallIsNot) {
  ContactProblem problem;
  problem.inverse_mass.assign(4, 1.0);
  problem.inverse_inertia.assign(4, 1.0);
  problem.free_velocity.assign(4, Vector3d::Zero());
  problem.free_angular_velocity.assign(4, Vector3d::Zero());
  problem.add_fixed_wall_bodies(2);
  problem.inverse_mass[problem.wall_body(-2)] = 0.5;  // wall 1 is a piston
  problem.resize_contacts(8);
  for (int k = 0; k < 8; ++k) {
    problem.body_i[k] = k % 4;
    problem.body_j[k] = k < 4 ? -1 : -2;  // every sphere touches both walls
  }
  ContactColouring colouring;
  colouring.update(problem);
  // Wall 0 (fixed): contacts 0-3 take colour 0. Wall 1 (piston): contacts 4-7 need four
  // colours, none of them 0 (each sphere already has colour 0).
  ASSERT_EQ(colouring.colour_count(), 5u);
  EXPECT_EQ(colouring.start()[1], 4);
  for (int k = 1; k < 5; ++k) EXPECT_EQ(colouring.start()[k + 1] - colouring.start()[k], 1);
}

TEST(ColouredGaussSeidel, FrictionalPileAtRestMatchesGaussSeidelAndStatics) {
  // Statics hold exactly; the solvers agree to the tolerance.
  const double tolerance = 1e-8;
  test::expect_pile_solved_like_gauss_seidel("nlgs_coloured", tolerance, 10 * tolerance);
}

TEST(ColouredGaussSeidel, SameBitsForAnyThreadCount) {
  const ContactProblem& problem = test::lattice_pile().problem();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    // 60 sweeps (not converged): the bits, not the answer, are compared, and a 2-thread
    // barrier per colour is slow on an oversubscribed machine.
    SolverSettings settings = test::tight(1e-12);
    settings.max_iterations = 60;
    settings.parallel_from = 0;  // parallel at any size
    ColouredGaussSeidelSolver solver(settings);
    return test::solve_cold(problem, solver);
  };
  const int threads_before = omp_get_max_threads();
  const test::Solved first = run(2), second = run(2), serial = run(1);
  omp_set_num_threads(threads_before);
  EXPECT_EQ(first.report.sweeps, 60);
  EXPECT_EQ(first.report.sweeps, second.report.sweeps);
  EXPECT_TRUE(same_bits(first.r, second.r));
  EXPECT_TRUE(same_bits(first.v, second.v));
  EXPECT_TRUE(same_bits(first.w, second.w));
  // 1 and 2 threads: within the tolerance (the contract), and in fact the same bits (the
  // contacts of a colour are independent, the sums add fixed blocks in order).
  test::expect_close_reactions(serial.r, first.r, 1e-8);
  EXPECT_EQ(first.report.sweeps, serial.report.sweeps);
  EXPECT_TRUE(same_bits(first.r, serial.r));
  EXPECT_TRUE(same_bits(first.v, serial.v));
}
