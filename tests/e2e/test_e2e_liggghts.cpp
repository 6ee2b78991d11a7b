// A real peer: LIGGGHTS pours and settles 100 spheres with the input of docs/import-dem.md, and
// tmdem runs the scene of that page on its dumps (DemImportCheck.h says what is checked).
// Skipped when `liggghts` is not installed (Debian package liggghts).
#include <gtest/gtest.h>

#include <cstdlib>

#include "DemImportCheck.h"

using namespace tmdem::e2e;

TEST(EndToEndLiggghts, PouredBedImportedWithItsForcesHeatsThroughHertzContacts) {
  if (std::system("command -v liggghts > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "liggghts is not installed (apt-get install liggghts)";
  const auto dir = scratch_dir("liggghts");
  const auto inputs = import_page_blocks("liggghts"), scenes = import_page_blocks("toml");
  ASSERT_FALSE(inputs.empty() || scenes.empty()) << "docs/import-dem.md lost its blocks";
  write_file(dir + "/pour.in", inputs.front());
  write_file(dir + "/bed.toml", scenes.front());
  ASSERT_EQ(std::system(("cd " + dir + " && liggghts -in pour.in -log log.liggghts > liggghts.out 2>&1").c_str()), 0)
      << "see " << dir << "/liggghts.out";
  const auto r = run_tmdem("run bed.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // LIGGGHTS' pair forces include friction; measured: 0.010289 N of 0.010273 N.
  expect_heated_bed(dir, 150, 0.02);
}
