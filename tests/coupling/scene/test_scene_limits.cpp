// The warning on a scene whose output would be huge (coupling/scene/SceneLimits.h): past 10 GB
// of estimated result file and XDMF, loading warns, names the frames and the estimate, and
// suggests the output.interval that brings it to at most 1 GB; loaded again at that interval the
// estimate is within 1 GB (to the part that does not grow with the frames) and the warning gone.
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
  EXPECT_LE(fitted_bytes, 1.0e9 + 1.0e6) << suggested;
  EXPECT_GT(fitted_bytes, 0.2e9) << suggested;  // rounded up to 1, 2 or 5: within a factor 5
  EXPECT_TRUE(fitted.warnings.empty());
  EXPECT_TRUE(load_scene_text(kBaseScene, "t").warnings.empty());
}

}  // namespace tmdem::coupling::test
