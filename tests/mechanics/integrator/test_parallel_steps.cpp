// OpenMP in the step loop (detection rebuilds and the contact set-up: frames, Delassus blocks,
// position terms): every loop writes only its own entries, so a step is the same bits whatever
// the thread count. Checked with parallel_from = 0 (threads at any size) on a pouring pile.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <vector>

#include "mechanics/SameBits.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/solvers/GaussSeidelSolver.h"
#include "mechanics/solvers/NncgSolver.h"

using namespace tmdem::mechanics;
using tmdem::mechanics::test::nlgs_parameters;
using Eigen::Vector3d;

namespace {

using tmdem::mechanics::test::same_bits;


struct Snapshot {
  std::vector<Vector3d> position, velocity, normal, tangent1, tangent2;
  std::vector<double> w_n, w_t, bias, mu;
  std::vector<std::int32_t> body_i, body_j;
  std::size_t rebuilds = 0;
};

Snapshot pour(int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  NscdParameters parameters = nlgs_parameters();
  parameters.parallel_from = 0;
  parameters.tolerance = 1e-4;
  parameters.max_iterations = 300;
  NscdIntegrator sim = test::random_pile(120, 3, 0.3, 11, parameters);
  for (int s = 0; s < 60; ++s) sim.step();
  omp_set_num_threads(before);
  const ContactProblem& p = sim.problem();
  return {sim.particles().position, sim.particles().velocity, p.normal, p.tangent1, p.tangent2,
          p.w_n, p.w_t, p.bias, p.mu, p.body_i, p.body_j, sim.detector().rebuild_count()};
}

}  // namespace

TEST(ParallelSteps, OneAndTwoThreadsStepTheSameBits) {
  const Snapshot one = pour(1), two = pour(2);
  ASSERT_GT(one.body_i.size(), 100u);
  EXPECT_GT(one.rebuilds, 1u);  // the pour rebuilt the table on the way
  EXPECT_EQ(one.rebuilds, two.rebuilds);
  EXPECT_TRUE(same_bits(one.body_i, two.body_i));
  EXPECT_TRUE(same_bits(one.body_j, two.body_j));
  EXPECT_TRUE(same_bits(one.normal, two.normal));
  EXPECT_TRUE(same_bits(one.tangent1, two.tangent1));
  EXPECT_TRUE(same_bits(one.tangent2, two.tangent2));
  EXPECT_TRUE(same_bits(one.w_n, two.w_n));
  EXPECT_TRUE(same_bits(one.w_t, two.w_t));
  EXPECT_TRUE(same_bits(one.bias, two.bias));
  EXPECT_TRUE(same_bits(one.mu, two.mu));
  EXPECT_TRUE(same_bits(one.position, two.position));
  EXPECT_TRUE(same_bits(one.velocity, two.velocity));
}

// NscdParameters::parallel_from reaches the contact solvers (SolverSettings::parallel_from):
// "nlgs" and "nncg" cut a pile of a few hundred contacts into slabs only when it is below it,
// and never at the default (4,096 contacts). One decision for both (ContactSlabs::update_if_large).
TEST(ParallelSteps, TheIntegratorsParallelFromReachesTheSolvers) {
  for (const char* solver : {"nlgs", "nncg"}) {
    auto sliced_after_a_step = [&](std::ptrdiff_t parallel_from) {
      NscdParameters parameters = nlgs_parameters();
      parameters.solver = solver;
      parameters.parallel_from = parallel_from;
      parameters.max_iterations = 50;
      NscdIntegrator sim = test::random_pile(200, 3, 0.3, 5, parameters);
      for (int s = 0; s < 40; ++s) sim.step();
      EXPECT_GT(sim.problem().size(), 100u) << solver;
      if (const auto* gs = dynamic_cast<const GaussSeidelSolver*>(&sim.solver())) return gs->sliced();
      return dynamic_cast<const NncgSolver&>(sim.solver()).sliced();
    };
    EXPECT_TRUE(sliced_after_a_step(0)) << solver;
    EXPECT_FALSE(sliced_after_a_step(kDefaultParallelFrom)) << solver;
  }
}
