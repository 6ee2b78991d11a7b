// NscdParameters::skip_out_of_reach: candidates farther apart than their two look-aheads leave
// the step's contact problem. Checked on a pile poured with nlgs (index order): while it falls
// candidates are left out, and where nothing is struck hard enough to outrun the look-aheads a
// candidate out of reach is one Gauss-Seidel would have left open (r = 0, no change, nothing
// added to the stop test), so this pile lands on the same bits as with every candidate in. (A
// resting particle struck within a step can outrun its own look-ahead: NscdParameters.h.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <cstdio>

#include "mechanics/MechanicsTestScenes.h"

namespace tmdem::mechanics::test {
namespace {

NscdParameters skipping(bool skip) {
  NscdParameters p = nlgs_parameters();
  p.skip_out_of_reach = skip;
  return p;
}

std::size_t unsolvable(const ContactProblem& problem) {
  std::size_t count = 0;
  for (std::size_t c = 0; c < problem.size(); ++c) count += problem.solvable(c) ? 0 : 1;
  return count;
}

}  // namespace

TEST(OutOfReach, FallingCandidatesLeaveTheProblemAndThePileLandsAlike) {
  NscdIntegrator all = random_pile(80, 3, 0.3, 5, skipping(false));
  NscdIntegrator skip = random_pile(80, 3, 0.3, 5, skipping(true));
  std::size_t left_out = 0, steps_with_forces = 0;
  double largest_difference_m = 0.0;
  for (int k = 0; k < 150; ++k) {
    const StepReport a = all.step();
    skip.step();
    EXPECT_EQ(unsolvable(all.problem()), 0u);
    left_out += unsolvable(skip.problem());
    // A contact with a reaction was never left out.
    for (std::size_t c = 0; c < skip.problem().size(); ++c) {
      if (!skip.problem().solvable(c)) {
        EXPECT_EQ(skip.reactions()[c].norm(), 0.0);
      }
    }
    steps_with_forces += a.active_contacts > 0 ? 1 : 0;
    for (std::size_t i = 0; i < all.particles().size(); ++i)
      largest_difference_m = std::max(
          largest_difference_m, (all.particles().position[i] - skip.particles().position[i]).norm());
  }
  EXPECT_GT(left_out, 0u) << "the falling pile should leave candidates out";
  EXPECT_GT(steps_with_forces, 0u) << "and should have landed";
  std::printf("[ reach    ] %zu candidates left out over 150 steps; positions differ by %.3g m\n",
              left_out, largest_difference_m);
  EXPECT_EQ(largest_difference_m, 0.0);
}

}  // namespace tmdem::mechanics::test
