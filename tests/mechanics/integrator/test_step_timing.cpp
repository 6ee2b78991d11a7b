// The wall time a Moreau-Jean step reports for its parts (StepReport::detection_s, solve_s,
// correction_s): never negative, together never more than the step took as timed from outside
// with the same steady clock, and summed exactly by MechanicsStats (the run's timing table and
// the summary's wall_time_parts read those sums).
#include <gtest/gtest.h>

#include <chrono>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

TEST(StepTiming, PartsAreNonNegativeWithinTheStepAndSummedByTheStats) {
  auto sim = random_pile(60, 3, 0.3, 7, nlgs_parameters());
  double detection = 0.0, solve = 0.0, correction = 0.0, outside = 0.0;
  for (int s = 0; s < 200; ++s) {
    const auto start = std::chrono::steady_clock::now();
    const StepReport r = sim.step();
    const double step_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_GE(r.detection_s, 0.0) << "step " << s;
    ASSERT_GE(r.solve_s, 0.0) << "step " << s;
    ASSERT_GE(r.correction_s, 0.0) << "step " << s;
    ASSERT_LE(r.detection_s + r.solve_s + r.correction_s, step_s) << "step " << s;
    detection += r.detection_s;
    solve += r.solve_s;
    correction += r.correction_s;
    outside += step_s;
  }
  // Every step detects and solves (the pile falls into contact); the clock reads ns.
  EXPECT_GT(detection, 0.0);
  EXPECT_GT(solve, 0.0);
  EXPECT_GT(correction, 0.0);  // the gaps after each step are computed at least
  EXPECT_LE(detection + solve + correction, outside);
  // Same additions in the same order: bitwise.
  EXPECT_EQ(sim.stats().detection_s, detection);
  EXPECT_EQ(sim.stats().solve_s, solve);
  EXPECT_EQ(sim.stats().correction_s, correction);
}
