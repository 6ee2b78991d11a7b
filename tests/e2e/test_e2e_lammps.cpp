// A real peer: LAMMPS pours and settles the 100 spheres of docs/import-dem.md with its own input
// (ids from property/local, forces from pair/local), and tmdem runs that page's scene with the
// columns the page names for LAMMPS (DemImportCheck.h says what is checked). Skipped when `lmp`
// is not installed (Debian package lammps).
#include <gtest/gtest.h>

#include <cstdlib>

#include "DemImportCheck.h"

using namespace tmdem::e2e;

TEST(EndToEndLammps, PouredBedImportedWithItsForcesHeatsThroughHertzContacts) {
  if (std::system("command -v lmp > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "lmp is not installed (apt-get install lammps)";
  const auto dir = scratch_dir("lammps");
  const auto inputs = import_page_blocks("lammps"), scenes = import_page_blocks("toml");
  ASSERT_EQ(inputs.size(), 1u) << "docs/import-dem.md lost its LAMMPS input";
  ASSERT_EQ(scenes.size(), 2u) << "docs/import-dem.md: the scene, then LAMMPS' contact_columns";
  // The page's scene with its contact_columns line replaced by the LAMMPS one.
  std::string scene = scenes[0];
  const auto line = scene.find("contact_columns");
  ASSERT_NE(line, std::string::npos);
  scene.replace(line, scene.find('\n', line) + 1 - line, scenes[1]);
  write_file(dir + "/pour.in", inputs.front());
  write_file(dir + "/bed.toml", scene);
  ASSERT_EQ(std::system(("cd " + dir + " && lmp -in pour.in -log log.lammps > lammps.out 2>&1").c_str()), 0)
      << "see " << dir << "/lammps.out";
  const auto r = run_tmdem("run bed.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // pair/local's force is the normal force only, so the balance misses the friction of the
  // pairs; measured: 0.0102648 N of 0.0102730 N.
  expect_heated_bed(dir, 150, 0.02);
}
