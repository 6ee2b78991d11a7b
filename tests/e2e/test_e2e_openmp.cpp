// End to end: the tmdem program waits passively at OpenMP barriers unless told otherwise
// (coupling/app/OpenMpWaitPolicy.h), and the summary says what the run used ("openmp").
// The policy only changes how idle threads wait, so the results are the same bits either way.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/wait.h>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// Runs `tmdem run` on the paper triangle (one settle step, 14 disks) with the given environment
// assignments (env(1) syntax; "-u NAME" removes NAME) and returns the summary.
nlohmann::json run_with_environment(const std::string& dir, const std::string& environment,
                                    const std::string& result) {
  const std::string cmd = "cd '" + dir + "' && env " + environment + " '" + TMDEM_BINARY +
                          "' run '" + std::string(TMDEM_SOURCE_DIR) +
                          "/examples/paper_triangle.toml' -o " + result + ".h5 --summary " +
                          result + ".json --quiet --set simulation.duration=0.5 > " + result +
                          ".log 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  return read_summary(dir + "/" + result + ".json");
}

TEST(EndToEndOpenMp, PassiveWaitUnlessTheUserChoseAndTheSummarySaysSo) {
  const auto dir = scratch_dir("openmp");
  const auto unset = run_with_environment(dir, "-u OMP_WAIT_POLICY OMP_NUM_THREADS=2", "unset");
  ASSERT_TRUE(unset.contains("openmp")) << unset.dump(2);
  EXPECT_EQ(unset["openmp"]["wait_policy"], "passive");
  EXPECT_EQ(unset["openmp"]["threads"], 2);

  const auto active = run_with_environment(dir, "OMP_WAIT_POLICY=active OMP_NUM_THREADS=1", "active");
  EXPECT_EQ(active["openmp"]["wait_policy"], "active");  // the user's choice is kept
  EXPECT_EQ(active["openmp"]["threads"], 1);

  // Same physics: the final temperatures of both runs are the same bits.
  const H5::H5File a(dir + "/unset.h5", H5F_ACC_RDONLY), b(dir + "/active.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_doubles(a, "/frames/temperature"), read_doubles(b, "/frames/temperature"));
  EXPECT_EQ(unset["energy"]["final_J"], active["energy"]["final_J"]);
}

}  // namespace
