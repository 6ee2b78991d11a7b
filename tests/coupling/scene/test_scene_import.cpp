// [[import]]: the CSV and LAMMPS dump readers give the file's exact values; bad files are
// refused naming FILE:LINE:COLUMN; the import table maps materials, scales and overrides; the
// overlap tolerance accepts a packing's own overlaps and reports the largest exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "coupling/scene/CsvPackingReader.h"
#include "coupling/scene/CsvPackingWriter.h"
#include "coupling/scene/LammpsDumpReader.h"
#include "tests/coupling/scene/ImportFolder.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// The message of the PackingFileError that reading throws.
template <typename Read>
std::string packing_error(Read read) {
  try {
    read();
  } catch (const PackingFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the file was read without error";
  return {};
}

TEST(ImportCsv, ReadsExactValuesSortedByIdAndListsIgnoredColumns) {
  const std::string text =
      "# a comment\n"
      "id, x,y,z,radius,material,temperature,fixed,vx\n"
      "\n"
      "7,0.25,-1e-3,3.5,0.125,glass,300.5,1,9\n"
      "2,1,2,3,4,steel,400,false,9\r\n";
  const Packing p = read_csv_packing(text, "p.csv", "temperature", true);
  ASSERT_EQ(p.rows.size(), 2u);
  EXPECT_EQ(p.rows[0].position, (Vec3{1.0, 2.0, 3.0}));  // id 2 first
  EXPECT_EQ(p.rows[0].radius, 4.0);
  EXPECT_EQ(p.rows[0].material, "steel");
  EXPECT_EQ(p.rows[0].temperature_K, 400.0);
  EXPECT_EQ(p.rows[0].fixed, false);
  EXPECT_EQ(p.rows[0].line, 5);
  EXPECT_EQ(p.rows[1].position, (Vec3{0.25, -1e-3, 3.5}));
  EXPECT_EQ(p.rows[1].radius, 0.125);
  EXPECT_EQ(p.rows[1].temperature_K, 300.5);
  EXPECT_EQ(p.rows[1].fixed, true);
  EXPECT_EQ(p.rows[1].line, 4);
  EXPECT_EQ(p.ignored_columns, std::vector<std::string>{"vx"});
}

TEST(ImportCsv, WriterOutputReadsBackBitForBit) {
  Packing p;
  for (int k = 0; k < 5; ++k) {
    PackingRow row;
    row.position = {0.1 * k + 1e-17, 1.0 / 3.0 * k, -2.0 / 7.0};
    row.radius = 1e-3 / (k + 3);
    row.material = k % 2 ? "glass" : "steel";
    row.temperature_K = 293.15 + 1.0 / 7.0 * k;
    p.rows.push_back(row);
  }
  const Packing back = read_csv_packing(packing_csv(p), "back.csv", "temperature", true);
  ASSERT_EQ(back.rows.size(), p.rows.size());
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    EXPECT_EQ(back.rows[k].position, p.rows[k].position);
    EXPECT_EQ(back.rows[k].radius, p.rows[k].radius);
    EXPECT_EQ(back.rows[k].material, p.rows[k].material);
    EXPECT_EQ(back.rows[k].temperature_K, p.rows[k].temperature_K);
  }
}

TEST(ImportCsv, BadFilesNameLineAndColumn) {
  const auto csv = [](const std::string& text) {
    return packing_error([&] { read_csv_packing(text, "b.csv", "temperature", true); });
  };
  EXPECT_EQ(csv("x,y,z,radius\n0,0,0,1\n0,0,0,0.0o1\n"),
            "b.csv:3:7: column radius: expected a finite number, got \"0.0o1\"");
  EXPECT_EQ(csv("x,y,z,radius\n0,0,0\n"), "b.csv:2: expected 4 values (one per column), got 3");
  EXPECT_EQ(csv("x,y,z,radius\n0,0,0,-1\n"), "b.csv:2:7: column radius: must be > 0, got -1");
  EXPECT_EQ(csv("x,y,z,radius,fixed\n0,0,0,1,yes\n"),
            "b.csv:2:9: column fixed: expected 0, 1, true or false, got \"yes\"");
  EXPECT_EQ(csv("x,y,z,radius\n0,nan,0,1\n"),
            "b.csv:2:3: column y: expected a finite number, got \"nan\"");
  EXPECT_NE(csv("x,y,radius\n0,0,1\n").find("b.csv:1: the header has no column z"),
            std::string::npos);
  EXPECT_EQ(csv("x,y,z,x,radius\n"), "b.csv:1:7: column x appears twice in the header");
  EXPECT_EQ(csv("id,x,y,z,radius\n1,0,0,0,1\n1,3,0,0,1\n"), "b.csv:3: id 1 also on line 2");
  EXPECT_EQ(csv("# only a comment\n"), "b.csv: no header line (the file is empty)");
}

const std::string kDump =
    "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id type x y z diameter\n1 1 9 9 9 2\n"
    "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id type xu yu zu diameter vx f_Temp[0]\n"
    "5 2 0.5 0.25 0.125 0.002 1 350.25\n"
    "3   1\t1.5 2.5 -3.5 0.004 0 310\n";

TEST(ImportLammps, ReadsTheLastSnapshotExactly) {
  const Packing p = read_lammps_dump(kDump, "d.dump", "f_Temp[0]", true);
  ASSERT_EQ(p.rows.size(), 2u);
  EXPECT_EQ(p.rows[0].position, (Vec3{1.5, 2.5, -3.5}));  // id 3 first
  EXPECT_EQ(p.rows[0].radius, 0.002);
  EXPECT_EQ(p.rows[0].type, 1);
  EXPECT_EQ(p.rows[0].temperature_K, 310.0);
  EXPECT_EQ(p.rows[0].line, 21);
  EXPECT_EQ(p.rows[1].position, (Vec3{0.5, 0.25, 0.125}));
  EXPECT_EQ(p.rows[1].radius, 0.001);
  EXPECT_EQ(p.rows[1].type, 2);
  EXPECT_EQ(p.rows[1].temperature_K, 350.25);
  EXPECT_EQ(p.ignored_columns, std::vector<std::string>{"vx"});
  EXPECT_TRUE(looks_like_lammps_dump(kDump));
  EXPECT_FALSE(looks_like_lammps_dump("x,y,z,radius\n"));
}

TEST(ImportLammps, BadDumpsNameLineAndColumn) {
  const auto dump = [](const std::string& text) {
    return packing_error([&] { read_lammps_dump(text, "d.dump", "temperature", true); });
  };
  const std::string head = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS\n0 1\n0 1\n0 1\n";
  EXPECT_EQ(dump(head + "ITEM: ATOMS id type x y z radius\n1 1 0 0 0 1\n"),
            "d.dump:11: the last snapshot ends after 1 of 2 atoms (NUMBER OF ATOMS)");
  EXPECT_EQ(dump(head + "ITEM: ATOMS id type x y z radius\n1 1 0 0 0 1\n2 1 0 0 x 1\n"),
            "d.dump:11:9: column z: expected a finite number, got \"x\"");
  EXPECT_EQ(dump(head + "ITEM: ATOMS id type xs ys zs radius\n"),
            "d.dump:9:21: scaled coordinates (xs) are not read; dump x y z or xu yu zu instead");
  EXPECT_EQ(dump("x y z\n"), "d.dump: no \"ITEM: TIMESTEP\" line: not a LAMMPS text dump");
}

// A scene file and its particle files in a fresh folder; the scene is loaded from there.
class SceneImport : public ImportFolder {
 protected:
  // base_scene (two particles, ids 0 and 1) plus one [[import]] with `keys`.
  std::string scene(const TomlKeys& keys) const { return base_scene().add("import", keys); }
};

TEST_F(SceneImport, ParticlesFollowTheScenesOwnWithMaterialsScaleOffsetAndOverrides) {
  const auto csv = file("p.csv", "x,y,z,radius,material,temperature\n"
                                 "10,5,0,1,glass,350\n"
                                 "20,5,0,1,steel,360\n");
  const Scene s = load_scene_text(
      scene({{"file", csv}, {"length_scale", 1e-3}, {"offset", {0.0, 0.001, 0.0}}, {"fixed", true}}),
      "test.toml");
  ASSERT_EQ(s.particles.size(), 4u);
  EXPECT_EQ(s.particles[2].position_m, (Vec3{10 * 1e-3, 5 * 1e-3 + 0.001, 0.0}));
  EXPECT_EQ(s.particles[2].radius_m, 1e-3);
  EXPECT_EQ(s.particles[2].material, 1);  // glass
  EXPECT_EQ(s.particles[3].material, 0);  // steel
  EXPECT_EQ(s.particles[2].temperature_K, 350.0);
  EXPECT_TRUE(s.particles[2].fixed && s.particles[3].fixed);
  ASSERT_EQ(s.imports.size(), 1u);
  EXPECT_EQ(s.imports[0].first_id, 2u);
  EXPECT_EQ(s.imports[0].count, 2u);
  EXPECT_EQ(s.imports[0].format, "csv");
  EXPECT_EQ(s.imports[0].largest_overlap, 0.0);

  // The table's material and temperature override the file's columns.
  const Scene o = load_scene_text(
      scene({{"file", csv}, {"length_scale", 1e-3}, {"offset", {0.0, 0.001, 0.0}},
             {"material", "glass"}, {"temperature", 280.0}}),
      "test.toml");
  EXPECT_EQ(o.particles[3].material, 1);
  EXPECT_EQ(o.particles[3].temperature_K, 280.0);
}

TEST_F(SceneImport, LammpsTypesMapToMaterials) {
  const auto dump = file("bed.dump", kDump);
  const Scene s = load_scene_text(
      scene({{"file", dump}, {"type_materials", raw("[\"steel\", \"glass\"]")}, {"offset", {0.0, 4.0, 0.0}},
             {"temperature_column", "f_Temp[0]"}}),
      "test.toml");
  ASSERT_EQ(s.particles.size(), 4u);
  EXPECT_EQ(s.imports[0].format, "lammps");
  EXPECT_EQ(s.particles[2].material, 0);  // type 1
  EXPECT_EQ(s.particles[3].material, 1);  // type 2
  EXPECT_EQ(s.particles[3].temperature_K, 350.25);
  expect_scene_error(scene({{"file", dump}, {"type_materials", raw("[\"steel\"]")}, {"offset", {0.0, 4.0, 0.0}}}),
                     {"import[0].file", "bed.dump:20: atom type 2 has no entry in "
                                        "import[0].type_materials (1 given, for types 1 to 1)"});
  expect_scene_error(scene({{"file", dump}, {"offset", {0.0, 4.0, 0.0}}}),
                     {"the file names no material (it has atom types: give type_materials)"});
}

TEST_F(SceneImport, ErrorsNameTheSceneKeyAndTheFilesLine) {
  const auto csv = file("bad.csv", "x,y,z,radius,material\n0,5,0,1,steel\n0,9,0,abc,steel\n");
  expect_scene_error(scene({{"file", csv}}),
                     {"test.toml:", "import[0].file: ", "bad.csv:3:7: column radius: expected a "
                                                        "finite number, got \"abc\""});
  const auto unknown = file("u.csv", "x,y,z,radius,material\n0,5,0,1,gold\n");
  expect_scene_error(scene({{"file", unknown}}),
                     {"u.csv:2: unknown material \"gold\""});
  expect_scene_error(scene({{"file", (dir_ / "missing.csv").string()}}), {"missing.csv: no such file"});
  expect_scene_error(scene({{"file", dir_.string()}}), {"not a regular file"});
  const auto off_plane = file("z.csv", "x,y,z,radius,material\n0.01,0.005,0.001,0.001,steel\n");
  expect_scene_error(base_scene().set("simulation.dimension", 2).add("import", {{"file", off_plane}}).str(),
                     {"z.csv:2: z = 0.001 in a 2D scene"});
  // In 2D the z column may be left out; in 3D it may not.
  const auto flat = file("flat.csv", "x,y,radius,material\n0.01,0.005,0.001,steel\n");
  const Scene s = load_scene_text(
      base_scene().set("simulation.dimension", 2).add("import", {{"file", flat}}).str(), "test.toml");
  EXPECT_EQ(s.particles.back().position_m, (Vec3{0.01, 0.005, 0.0}));
  expect_scene_error(scene({{"file", flat}}), {"flat.csv:1: the header has no column z"});
}

TEST_F(SceneImport, OverlapToleranceAcceptsThePackingsOwnOverlapsAndReportsTheLargest) {
  // Radii 1 mm at centre distance 1.99 mm: overlap 0.01 mm = 0.01 of the radius; the second pair
  // (radii 1 and 0.5 mm at 1.49 mm) overlaps 0.01 mm = 0.02 of the smaller radius.
  const auto csv = file("o.csv", "x,y,z,radius,material\n"
                                 "0.010,0.005,0,0.001,steel\n"
                                 "0.01199,0.005,0,0.001,steel\n"
                                 "0.01348,0.005,0,0.0005,steel\n");
  expect_scene_error(scene({{"file", csv}}),
                     {"particles 2 and 3 overlap at start", "import[0].overlap_tolerance = 1e-09",
                      "(2 overlapping pairs in all)"});
  expect_scene_error(scene({{"file", csv}, {"overlap_tolerance", 0.015}}),
                     {"particles 3 and 4 overlap at start"});
  const Scene s = load_scene_text(scene({{"file", csv}, {"overlap_tolerance", 0.025}}), "test.toml");
  EXPECT_NEAR(s.imports[0].largest_overlap, 0.02, 1e-12);
  EXPECT_NEAR(s.imports[0].largest_overlap_m, 1e-5, 1e-17);
  EXPECT_EQ(s.imports[0].largest_overlap_between, "particles 3 and 4");
  // The refusal names the deepest overlap of the file and a tolerance that accepts it, which
  // does: a user handed a packing made at a softened modulus need not guess.
  const std::string refused = scene_error(scene({{"file", csv}}));
  EXPECT_NE(refused.find("the deepest overlap of import[0] is 0.02"), std::string::npos) << refused;
  EXPECT_NE(refused.find("(particles 3 and 4)"), std::string::npos) << refused;
  const std::string key = "overlap_tolerance = ";
  const std::size_t at = refused.find(key, refused.find("the deepest overlap"));
  ASSERT_NE(at, std::string::npos) << refused;
  const double suggested = std::stod(refused.substr(at + key.size()));
  EXPECT_GE(suggested, 0.02);
  EXPECT_LE(suggested, 0.021);
  EXPECT_NO_THROW(load_scene_text(scene({{"file", csv}, {"overlap_tolerance", suggested}}), "test.toml"));
  // The same when the deepest overlap is a wall's: the base scene's floor at y = 0 cuts a
  // sphere of radius 1 mm by 0.03 of its radius.
  const auto floor = file("f.csv", "x,y,z,radius,material\n0.010,0.00097,0,0.001,steel\n");
  const std::string wall_refused = scene_error(scene({{"file", floor}}));
  EXPECT_NE(wall_refused.find("and wall["), std::string::npos) << wall_refused;
  EXPECT_NE(wall_refused.find("overlap_tolerance = 0.03 accepts every overlap"), std::string::npos) << wall_refused;
  // The tolerance is the import's own: its particles may not overlap the scene's others.
  const auto onto = file("onto.csv", "x,y,z,radius,material\n0.00199,0.001,0,0.001,steel\n");
  expect_scene_error(scene({{"file", onto}, {"overlap_tolerance", 0.1}}),
                     {"particles 0 and 2 overlap at start", "allowed down to -1e-9"});
}

}  // namespace
}  // namespace tmdem::coupling::test
