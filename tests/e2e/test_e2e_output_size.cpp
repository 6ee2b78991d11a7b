// End to end: `tmdem check`'s output estimate against the files a run writes (result + XDMF),
// for a settled (frozen) bed and a dynamic pour. The estimate is rough by design (contacts at
// 3 per particle): it must stay within a factor 2 of the truth, never below half of it.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

double estimated_bytes(const std::string& scene, const std::string& dir) {
  const auto r = run_tmdem("check '" + scene + "'", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::smatch m;
  EXPECT_TRUE(std::regex_search(r.output, m, std::regex("frames, about ([0-9.e+-]+) MB")))
      << r.output;
  return m.empty() ? 0.0 : std::stod(m[1].str()) * 1e6;
}

}  // namespace

TEST(EndToEndOutputSize, CheckEstimateIsWithinAFactorTwoOfTheWrittenFiles) {
  for (const std::string example : {"paper_bed", "poured_bed"}) {
    const auto dir = scratch_dir("output_size_" + example);
    const std::string scene = std::string(TMDEM_SOURCE_DIR) + "/examples/" + example + ".toml";
    const double estimate = estimated_bytes(scene, dir);
    const auto r = run_tmdem("run '" + scene + "' --quiet -o out.h5", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const double written = double(std::filesystem::file_size(dir + "/out.h5") +
                                  std::filesystem::file_size(dir + "/out.xdmf"));
    EXPECT_GT(estimate, 0.5 * written) << example << ": " << estimate << " vs " << written;
    EXPECT_LT(estimate, 2.0 * written) << example << ": " << estimate << " vs " << written;
  }
}
