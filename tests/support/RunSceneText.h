#pragma once
// Runs a scene given as TOML text into a scratch folder (removed afterwards) and returns the
// outcome; the log is appended to outcome.summary.message when the run did not exit 0.
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "coupling/run/CoupledRun.h"
#include "coupling/scene/SceneLoader.h"

namespace tmdem::test {

inline coupling::RunOutcome run_scene_text(const std::string& text, const std::string& name) {
  const auto scene = coupling::load_scene_text(text, name);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tmdem_run_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  coupling::RunOptions options;
  options.output_path = (dir / "out.h5").string();
  options.quiet = true;
  std::ostringstream log;
  auto outcome = coupling::run_scene(scene, options, log);
  std::filesystem::remove_all(dir);
  if (outcome.exit_code != 0) outcome.summary.message += log.str();
  return outcome;
}

}  // namespace tmdem::test
