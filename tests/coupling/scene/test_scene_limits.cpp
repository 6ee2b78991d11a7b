// The warning on a scene whose output would be huge (coupling/scene/SceneLimits.h): past 10 GB
// of estimated result file and XDMF, loading warns, names the frames and the estimate, and
// suggests the output.interval that brings it to at most 1 GB; loaded again at that interval the
// estimate is within 1 GB and the warning gone.
#include <gtest/gtest.h>

#include <string>

#include "coupling/scene/SceneLimits.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {

TEST(SceneLimits, AHugeOutputIsWarnedOfWithAnIntervalThatFitsAGigabyte) {
  // 9,000,000 frames of the base scene's two particles (the limit is 10^7 frames).
  const std::vector<std::string> long_run = {"simulation.duration=900000.0", "output.interval=0.1"};
  const Scene scene = load_scene_text(kBaseScene, "t", long_run);
  const double bytes = estimate_resources(scene).output_bytes;
  ASSERT_GT(bytes, kWarnOutputBytes);
  ASSERT_LT(bytes, kMaxOutputBytes);  // legal
  ASSERT_EQ(scene.warnings.size(), 1u);
  const std::string& warning = scene.warnings[0];
  EXPECT_NE(warning.find("output.interval = 0.1 s gives 9000002 frames of 2 particles"), std::string::npos)
      << warning;
  EXPECT_NE(warning.find(" GB"), std::string::npos) << warning;
  EXPECT_EQ(warning, large_output_warning(scene));

  // The suggestion: "output.interval = X s gives at most 1 GB".
  const std::string key = "; output.interval = ";
  const std::size_t at = warning.find(key);
  ASSERT_NE(at, std::string::npos) << warning;
  const std::string suggested = warning.substr(at + key.size(), warning.find(' ', at + key.size()) - at - key.size());
  const double suggested_s = std::stod(suggested);
  EXPECT_GT(suggested_s, 0.1);
  const Scene fitted = load_scene_text(kBaseScene, "t", {long_run[0], "output.interval=" + suggested});
  const double fitted_bytes = estimate_resources(fitted).output_bytes;
  EXPECT_LE(fitted_bytes, 1.0e9) << suggested;
  EXPECT_GT(fitted_bytes, 0.2e9) << suggested;  // the first rung of 1, 2, 5 that fits: within 5x
  EXPECT_TRUE(fitted.warnings.empty());
  EXPECT_TRUE(load_scene_text(kBaseScene, "t").warnings.empty());
}

// No interval helps a run whose first and last frames alone pass the target: the warning says
// so instead of suggesting one. (Shown with the thresholds scaled down to the base scene's
// few-kB output: a real case needs millions of particles.)
TEST(SceneLimits, NoIntervalIsSuggestedWhenTheFirstAndLastFramesPassTheTarget) {
  const Scene scene = load_scene_text(kBaseScene, "t", {"simulation.duration=0.1", "output.interval=0.1"});
  const double bytes = estimate_resources(scene).output_bytes;  // 3 frames
  EXPECT_TRUE(large_output_warning(scene, bytes, bytes / 10.0).empty());  // not past the warning
  const std::string warning = large_output_warning(scene, bytes / 2.0, bytes / 10.0);
  EXPECT_NE(warning.find("gives 3 frames of 2 particles"), std::string::npos) << warning;
  EXPECT_NE(warning.find("even its first and last frames pass"), std::string::npos) << warning;
  EXPECT_EQ(warning.find("gives at most"), std::string::npos) << warning;
  // A run of 1,002 frames, with the thresholds at the same fractions of its own estimate, gets
  // an interval.
  const Scene longer = load_scene_text(kBaseScene, "t", {"simulation.duration=100.0", "output.interval=0.1"});
  const double longer_bytes = estimate_resources(longer).output_bytes;
  EXPECT_NE(large_output_warning(longer, longer_bytes / 2.0, longer_bytes / 10.0).find("s gives at most"),
            std::string::npos);
}

}  // namespace tmdem::coupling::test
