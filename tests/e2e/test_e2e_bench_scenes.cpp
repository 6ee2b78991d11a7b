// The scenes of bench/ (the 10^6 lattice, our own beds of bench/beds/) are read by users and by
// bench/settle_beds.py: every one passes `tmdem check`, so a change of the scene schema cannot
// leave them behind unnoticed (their runs take minutes and are measured, not tested).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "E2eSupport.h"

using namespace tmdem::e2e;
namespace fs = std::filesystem;

TEST(EndToEndBenchScenes, EveryBenchSceneIsValid) {
  const fs::path bench = fs::path(TMDEM_SOURCE_DIR) / "bench";
  std::vector<fs::path> scenes;
  for (const fs::path& folder : {bench, bench / "beds"})
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  // The thirty-one beds of bench/beds and the lattice: a folder that lost its scenes fails too.
  ASSERT_GE(scenes.size(), 32u);
  const std::string dir = scratch_dir("bench_scenes");
  for (const fs::path& scene : scenes) {
    // From the scene's own folder, as bench/settle_beds.py runs it: an import's file is named
    // relative to the current folder (the contract), beside the scene.
    const ProgramResult r = run_tmdem_from("check '" + scene.filename().string() + "'", scene.parent_path().string(), dir);
    EXPECT_EQ(r.exit_code, 0) << scene << ":\n" << r.output;
    EXPECT_NE(r.output.find("scene is valid"), std::string::npos) << scene << ":\n" << r.output;
  }
}
