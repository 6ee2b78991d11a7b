// Stability suite: an injected right-hand-side failure stops the run cleanly. The failure comes
// from the test-only fault_injection mode, which only the test program tmdem_testing registers.
#include <gtest/gtest.h>

#include <H5Cpp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/SceneBuilder.h"

using namespace tmdem::test;

TEST(StabilityFailure, InjectedRhsFailureExitsThreeKeepsFramesAndMarksFailed) {
  const auto dir = std::filesystem::temp_directory_path() / ("tmdem_fault_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "s.toml") << thermal_scene()
                                         .set("simulation.duration", 50.0)
                                         .add("generate", column(4))
                                         .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
                                         .set(output("out.h5", 0.5))
                                         .set("effects.fault_injection", true)
                                         .set("fault_injection.after_rhs_evaluations", 40);
  }
  const std::string cmd = "cd '" + dir.string() + "' && '" + TMDEM_TESTING_BINARY +
                          "' run s.toml --summary s.json > log.txt 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  std::stringstream log;
  log << std::ifstream(dir / "log.txt").rdbuf();
  EXPECT_NE(log.str().find("CV_REPTD_RHSFUNC_ERR"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("right-hand side"), std::string::npos) << log.str();

  H5::H5File f((dir / "out.h5").string(), H5F_ACC_RDONLY);
  H5::Attribute a = f.openAttribute("status");
  std::string st;
  a.read(a.getStrType(), st);
  EXPECT_EQ(st, "failed");
  H5::DataSet time = f.openDataSet("/frames/time");
  hsize_t frames = 0;
  time.getSpace().getSimpleExtentDims(&frames);
  EXPECT_GE(frames, 2u);    // frames written before the failure are kept
  EXPECT_LT(frames, 101u);  // and the run did stop
  std::vector<double> T(frames * 4);
  f.openDataSet("/frames/temperature").read(T.data(), H5::PredType::NATIVE_DOUBLE);
  for (double x : T) {
    EXPECT_TRUE(std::isfinite(x));
    EXPECT_GE(x, 293.15 - 1e-9);
    EXPECT_LE(x, 373.15 + 1e-9);
  }
  std::stringstream summary;
  summary << std::ifstream(dir / "s.json").rdbuf();
  EXPECT_NE(summary.str().find("\"status\": \"failed\""), std::string::npos) << summary.str();
  std::filesystem::remove_all(dir);
}
