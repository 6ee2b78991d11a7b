// End to end: the tmdem program bounds the spin of idle OpenMP threads and takes one thread per
// idle core unless told otherwise (coupling/app/OpenMpWaitPolicy.h), and the summary says what
// the run used ("openmp"). How idle threads wait changes no result: the same bits either way.
#include <gtest/gtest.h>

#include <omp.h>

#include <cstdlib>
#include <sys/wait.h>

#include "E2eSupport.h"
#include "coupling/app/OpenMpWaitPolicy.h"

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

TEST(EndToEndOpenMp, BoundedSpinUnlessTheUserChoseAndTheSummarySaysSo) {
  const auto dir = scratch_dir("openmp");
  const auto unset =
      run_with_environment(dir, "-u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_NUM_THREADS=2", "unset");
  ASSERT_TRUE(unset.contains("openmp")) << unset.dump(2);
  EXPECT_EQ(unset["openmp"]["wait_policy"], "unset");
  EXPECT_EQ(unset["openmp"]["spin_count"], tmdem::coupling::kSpinCount);
  EXPECT_EQ(unset["openmp"]["threads"], 2);

  const auto active = run_with_environment(dir, "OMP_WAIT_POLICY=active OMP_NUM_THREADS=1", "active");
  EXPECT_EQ(active["openmp"]["wait_policy"], "active");  // the user's choice is kept
  EXPECT_EQ(active["openmp"]["spin_count"], "unset");
  EXPECT_EQ(active["openmp"]["threads"], 1);

  // Same physics: the final temperatures of both runs are the same bits.
  const H5::H5File a(dir + "/unset.h5", H5F_ACC_RDONLY), b(dir + "/active.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_doubles(a, "/frames/temperature"), read_doubles(b, "/frames/temperature"));
  EXPECT_EQ(unset["energy"]["final_J"], active["energy"]["final_J"]);
}

// Without OMP_NUM_THREADS the run takes one thread per idle core: the cores less the rounded
// 1-minute load average, at least one.
TEST(EndToEndOpenMp, WithoutAThreadCountOneThreadPerIdleCore) {
  using tmdem::coupling::idle_cores;
  EXPECT_EQ(idle_cores(2, 0.3), 2);
  EXPECT_EQ(idle_cores(2, 0.6), 1);
  EXPECT_EQ(idle_cores(2, 5.0), 1);
  EXPECT_EQ(idle_cores(8, 3.2), 5);
  EXPECT_EQ(idle_cores(8, NAN), 8);
  EXPECT_EQ(idle_cores(0, 0.0), 1);
  const auto dir = scratch_dir("openmp_idle");
  const auto chosen = run_with_environment(dir, "-u OMP_NUM_THREADS", "idle");
  EXPECT_GE(chosen["openmp"]["threads"].get<int>(), 1);
  EXPECT_LE(chosen["openmp"]["threads"].get<int>(), omp_get_num_procs());
}

}  // namespace
