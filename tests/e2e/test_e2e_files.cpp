// End to end: no file is ever lost silently (existing results, the scene file, another scene's
// result on --restart, a second writer), I/O faults end with exit 4 and never a crash, absurd
// scenes are refused before anything is written, and SIGTERM ends a run cleanly.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "E2eSupport.h"

using namespace tmdem::e2e;
namespace fs = std::filesystem;

namespace {

// A small thermal-only lattice (mechanics off): runs in milliseconds.
std::string lattice_scene(int nx, double conductance_W_per_K) {
  using namespace tmdem::test;
  return thermal_scene()
      .set({{"simulation.duration", 4.0},
            {"thermal.constant_conductance", conductance_W_per_K},
            {"output.file", "out.h5"},
            {"output.interval", 1.0},
            {"output.checkpoint_interval", 2.0}})
      .add("generate", lattice({nx, 2, 2}))
      .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
      .str();
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Files in `dir` other than the scene and the program's log.
std::vector<std::string> outputs_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 5 && name.substr(name.size() - 5) == ".toml") continue;
    if (name == "tmdem.log") continue;
    names.push_back(name);
  }
  return names;
}

TEST(EndToEndFiles, ExistingResultIsNotOverwrittenWithoutOverwrite) {
  const auto dir = scratch_dir("files_overwrite");
  write_file(dir + "/s.toml", lattice_scene(3, 1e-3));
  ASSERT_EQ(run_tmdem("run s.toml --quiet", dir).exit_code, 0);
  const std::string before = bytes_of(dir + "/out.h5");
  auto r = run_tmdem("run s.toml --quiet --set thermal.constant_conductance=2e-3", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("out.h5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--overwrite"), std::string::npos) << r.output;
  EXPECT_EQ(bytes_of(dir + "/out.h5"), before);
  r = run_tmdem("run s.toml --quiet --overwrite --set thermal.constant_conductance=2e-3", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(bytes_of(dir + "/out.h5"), before);
}

// -o overrides output.file (contract): the result file's resolved scene says where it was
// written, quotes and backslashes in the name included.
TEST(EndToEndFiles, OutputOptionIsInTheResolvedScene) {
  const auto dir = scratch_dir("files_o");
  write_file(dir + "/s.toml", lattice_scene(3, 1e-3));
  const std::string name = "a \"quoted\" \\ name.h5";
  const auto r = run_tmdem("run s.toml --quiet -o 'a \"quoted\" \\ name.h5'", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(dir + "/" + name));
  H5::H5File f(dir + "/" + name, H5F_ACC_RDONLY);
  const toml::table scene = toml::parse(read_string_attribute(f, "scene"));
  EXPECT_EQ(scene["output"]["file"].value<std::string>(), name);
}

TEST(EndToEndFiles, SceneFileAndEmptyNameAreNeverOutputs) {
  const auto dir = scratch_dir("files_scene");
  const std::string scene = lattice_scene(3, 1e-3);
  write_file(dir + "/s.toml", scene);
  for (const std::string args : {"run s.toml -o s.toml", "run s.toml -o ./s.toml --overwrite",
                                  "run s.toml -o ''", "run s.toml --summary s.toml"}) {
    SCOPED_TRACE(args);
    const auto r = run_tmdem(args, dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(bytes_of(dir + "/s.toml"), scene);
    EXPECT_TRUE(outputs_in(dir).empty()) << r.output;
  }
  EXPECT_NE(run_tmdem("run s.toml -o s.toml", dir).output.find("s.toml' is the scene file"),
            std::string::npos);
}

TEST(EndToEndFiles, RestartOntoAnotherScenesResultIsRefusedAndLeavesItUnchanged) {
  const auto dir = scratch_dir("files_restart");
  write_file(dir + "/a.toml", lattice_scene(3, 1e-3));
  write_file(dir + "/b.toml", lattice_scene(4, 1e-3));   // other particle count
  write_file(dir + "/c.toml", lattice_scene(3, 5e-3));   // same count, other physics
  ASSERT_EQ(run_tmdem("run a.toml --quiet -o a.h5", dir).exit_code, 0);
  ASSERT_EQ(run_tmdem("run b.toml --quiet -o b.h5", dir).exit_code, 0);
  ASSERT_EQ(run_tmdem("run c.toml --quiet -o c.h5", dir).exit_code, 0);
  ASSERT_TRUE(fs::exists(dir + "/a.checkpoint.h5"));
  for (const std::string target : {"b.h5", "c.h5"}) {
    SCOPED_TRACE(target);
    const std::string before = bytes_of(dir + "/" + target);
    const auto r = run_tmdem("run a.toml --quiet --restart a.checkpoint.h5 -o " + target, dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(target), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(dir + "/" + target), before);
  }
  // The matching file is accepted.
  EXPECT_EQ(run_tmdem("run a.toml --quiet --restart a.checkpoint.h5 -o a.h5", dir).exit_code, 0);
}

// Runs the program under a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored): every write past
// `limit_kb` kB fails with EFBIG, as on a full disk.
ProgramResult run_with_file_limit(const std::string& args, const std::string& dir, int limit_kb) {
  const std::string log = dir + "/tmdem.log";
  const std::string script = "cd '" + dir + "' && trap '' XFSZ && ulimit -f " +
                             std::to_string(limit_kb) + " && exec '" + TMDEM_BINARY + "' " + args;
  const std::string command = "bash -c \"" + script + "\" > '" + log + "' 2>&1";
  const int status = std::system(command.c_str());
  ProgramResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = bytes_of(log);
  return r;
}

TEST(EndToEndFiles, FullDiskEndsWithExit4AndOneMessageNeverACrash) {
  const auto dir = scratch_dir("files_full");
  write_file(dir + "/s.toml", lattice_scene(20, 1e-3));
  for (int limit_kb : {4, 12, 40, 200}) {
    SCOPED_TRACE(limit_kb);
    for (const auto& name : outputs_in(dir)) fs::remove(dir + "/" + name);
    const auto r = run_with_file_limit("run s.toml --quiet --set simulation.duration=200 "
                                       "--set output.interval=0.5",
                                       dir, limit_kb);
    EXPECT_EQ(r.exit_code, 4) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << r.output;
    EXPECT_EQ(count_of(r.output, "error:"), 1u) << r.output;
    EXPECT_NE(r.output.find("out.h5"), std::string::npos) << r.output;
  }
}

TEST(EndToEndFiles, AbsurdScenesAreRefusedNamingTheKeyAndNothingIsWritten) {
  const auto dir = scratch_dir("files_limits");
  write_file(dir + "/s.toml", lattice_scene(3, 1e-3));
  std::string tiny = lattice_scene(3, 1e-3);
  tiny.replace(tiny.find("radius = 0.001"), 14, "radius = 1e-300");
  write_file(dir + "/tiny.toml", tiny);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"s.toml --set simulation.duration=1e300", "simulation.duration"},
      {"s.toml --set output.interval=1e-300", "output.interval"},
      {"tiny.toml", "generate[0].radius"},
  };
  for (const auto& [args, key] : cases) {
    SCOPED_TRACE(args);
    const auto r = run_tmdem("run --summary s.json " + args, dir);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << r.output;
    EXPECT_TRUE(outputs_in(dir).empty()) << r.output;
  }
}

}  // namespace
