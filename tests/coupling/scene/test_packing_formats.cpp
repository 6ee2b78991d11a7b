// [[import]] formats come from one table (coupling/scene/PackingFormats.cpp): the schema's
// choices, how format = "auto" picks one (by ending, then by text), and the message when it
// cannot, all read the table; each name reaches its own reader.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "coupling/scene/PackingFormats.h"
#include "coupling/scene/SceneSchema.h"
#include "tests/coupling/scene/ImportFolder.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {

TEST(PackingFormats, TheSchemaChoicesAreTheTablesNames) {
  const std::vector<std::string> names{"auto", "csv", "lammps", "tmdem"};
  EXPECT_EQ(packing_format_choices(), names);
  const auto* format = SceneSchema::find("import", "format");
  ASSERT_NE(format, nullptr);
  EXPECT_EQ(format->choices, names);
  for (const auto& name : names)
    EXPECT_EQ(find_packing_format(name) != nullptr, name != "auto") << name;
  EXPECT_EQ(find_packing_format("vtk"), nullptr);
}

TEST(PackingFormats, AutoPicksByEndingThenByText) {
  EXPECT_EQ(packing_format_by_ending("bed.csv")->name, "csv");
  EXPECT_EQ(packing_format_by_ending("BED.CSV")->name, "csv");
  EXPECT_EQ(packing_format_by_ending("run.h5")->name, "tmdem");
  EXPECT_EQ(packing_format_by_ending("run.hdf5")->name, "tmdem");
  EXPECT_EQ(packing_format_by_ending("bed.dump"), nullptr);
  EXPECT_EQ(packing_format_by_ending("bed.csv.txt"), nullptr);
  EXPECT_EQ(packing_format_by_text("\n  ITEM: TIMESTEP\n0\n")->name, "lammps");
  EXPECT_EQ(packing_format_by_text("x,y,z,radius\n"), nullptr);
  EXPECT_EQ(unknown_packing_format_hint(),
            "(not .csv, .CSV, .h5 or .hdf5, and no \"ITEM:\" first line); give format = "
            "\"csv\", \"lammps\" or \"tmdem\"");
}

class PackingFormatImport : public ImportFolder {};

// The same particles as CSV named .txt: "auto" cannot tell, format = "csv" reads them, and
// format = "lammps" hands them to the dump reader, which refuses them.
TEST_F(PackingFormatImport, EachNameReachesItsReader) {
  const auto path = file("bed.txt", "x,y,z,radius,material\n0.01,0.005,0,0.001,steel\n");
  const auto scene = [&](const char* format) {
    return base_scene().add("import", {{"file", path}, {"format", format}}).str();
  };
  expect_scene_error(scene("auto"), {"import[0].file", "cannot tell the format of",
                                     "bed.txt", unknown_packing_format_hint()});
  const Scene csv = load_scene_text(scene("csv"), "test.toml");
  ASSERT_EQ(csv.imports.size(), 1u);
  EXPECT_EQ(csv.imports[0].format, "csv");
  EXPECT_EQ(csv.particles.back().position_m, (Vec3{0.01, 0.005, 0.0}));
  expect_scene_error(scene("lammps"), {"import[0].file", "bed.txt"});
  expect_scene_error(scene("vtk"), {"import[0].format", "\"auto\", \"csv\", \"lammps\", \"tmdem\""});
}

}  // namespace tmdem::coupling::test
