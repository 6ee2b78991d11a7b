// BlockedSum.h: sums over contacts shared by threads in blocks of a fixed size, so that any
// thread count gives the same bits, and a problem of one block is summed as the plain loop.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/contact/BlockedSum.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/SiconosResidual.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace blocked_sum_test {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Terms of many magnitudes, so that the order of the additions shows in the last bits.
double term_of(std::size_t c) { return std::ldexp(1.0 + 0.37 * std::sin(double(c)), int(c % 41) - 20); }

// Runs f on 1, 2 and 3 threads; the three results.
template <class F>
std::vector<double> on_threads(F&& f) {
  const int before = omp_get_max_threads();
  std::vector<double> out;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    out.push_back(f());
  }
  omp_set_num_threads(before);
  return out;
}

}  // namespace blocked_sum_test

using blocked_sum_test::on_threads;
using blocked_sum_test::term_of;

TEST(BlockedSum, OneBlockIsThePlainLoopAndBlocksGiveTheSameBitsForAnyThreadCount) {
  const auto sum_of = [](std::size_t count) {
    return blocked_sum<double>(count, [](std::size_t c, double& sum) { sum += term_of(c); });
  };
  // One block: the loop's own order, to the bit.
  double plain = 0.0;
  for (std::size_t c = 0; c < 1000; ++c) plain += term_of(c);
  EXPECT_TRUE(blocked_sum_test::same_bits(sum_of(1000), plain));
  // Three and a bit blocks: the blocks summed in order, each in index order, whatever the threads.
  const std::size_t count = 3 * kBlockedSumBlock + 123;
  double by_blocks = 0.0;
  for (std::size_t first = 0; first < count; first += kBlockedSumBlock) {
    double block = 0.0;
    for (std::size_t c = first; c < std::min(count, first + kBlockedSumBlock); ++c) block += term_of(c);
    by_blocks += block;
  }
  long double exact = 0.0L;
  for (std::size_t c = 0; c < count; ++c) exact += term_of(c);
  for (const double sum : on_threads([&] { return sum_of(count); })) {
    EXPECT_TRUE(blocked_sum_test::same_bits(sum, by_blocks)) << sum << " against " << by_blocks;
    EXPECT_NEAR(sum, double(exact), 1e-14 * double(exact));
  }
  // Two sums at once.
  const SumPair pair = blocked_sum<SumPair>(count, [](std::size_t c, SumPair& sum) {
    sum.first += term_of(c);
    sum.second += 1.0;
  });
  EXPECT_TRUE(blocked_sum_test::same_bits(pair.first, by_blocks));
  EXPECT_EQ(pair.second, double(count));
}

// The residuals a step measures, on a falling pile with rolling resistance of more than two
// blocks of candidates: the same bits on 1, 2 and 3 threads.
TEST(BlockedSum, ResidualsOfALargeProblemHaveTheSameBitsForAnyThreadCount) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-4;
  parameters.max_iterations = 200;
  NscdIntegrator sim = random_pile(3000, 3, 0.5, 3, parameters, 0.05, 2.2);
  for (int step = 0; step < 12; ++step) sim.step();
  const ContactProblem& problem = sim.problem();
  ASSERT_TRUE(problem.rolling);
  ASSERT_GT(problem.size(), 2 * kBlockedSumBlock);
  std::vector<Eigen::Vector3d> r = sim.reactions(), m(problem.size(), Eigen::Vector3d::Zero()), v, w;
  problem.velocities_from_reactions(r, m, v, w);
  const auto q = on_threads([&] { return free_velocity_norm(problem); });
  const auto e = on_threads([&] { return siconos_residual(problem, r, m, v, w, q[0]); });
  const auto natural = on_threads([&] { return natural_map_residual(problem, r, m, v, w); });
  ASSERT_GT(q[0], 0.0);
  ASSERT_GT(e[0], 0.0);
  ASSERT_GT(natural[0], 0.0);
  for (int k = 1; k < 3; ++k) {
    EXPECT_TRUE(blocked_sum_test::same_bits(q[k], q[0])) << k;
    EXPECT_TRUE(blocked_sum_test::same_bits(e[k], e[0])) << k;
    EXPECT_TRUE(blocked_sum_test::same_bits(natural[k], natural[0])) << k;
  }
}
