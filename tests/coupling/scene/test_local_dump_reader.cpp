// [[import]] contacts: the LAMMPS / LIGGGHTS local dump reader gives the file's exact values of
// the snapshot matching the particle dump (else the last); bad files are refused naming
// FILE:LINE(:COLUMN); the import maps the dump's ids to scene particles and takes the normal
// part of a force vector.
#include <gtest/gtest.h>

#include "coupling/scene/LocalDumpReader.h"
#include "coupling/scene/PackingFile.h"
#include "tests/coupling/scene/ImportFolder.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// A local dump of `entries` lines under the header `columns`, at `step`.
std::string local_snapshot(long long step, const std::string& columns,
                           const std::vector<std::string>& entries) {
  std::string out = "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF ENTRIES\n" +
                    std::to_string(entries.size()) +
                    "\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ENTRIES " + columns + "\n";
  for (const auto& e : entries) out += e + "\n";
  return out;
}

std::string local_error(const std::string& text, const LocalDumpColumns& columns = {},
                        std::optional<long long> step = std::nullopt) {
  try {
    read_local_dump(text, "c.dump", columns, step, "p.dump");
  } catch (const PackingFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the file was read without error";
  return {};
}

TEST(LocalDump, ReadsTheMatchingSnapshotExactly) {
  const std::string text = local_snapshot(100, "id1 id2 fn", {"1 2 0.5"}) +
                           local_snapshot(200, "id2 fn id1", {"3 0.125 2", "1 2.5e-3 2"}) +
                           local_snapshot(300, "id1 id2 fn", {});
  const auto last = read_local_dump(text, "c.dump", {}, std::nullopt, "p.dump");
  EXPECT_EQ(last.timestep, 300);
  EXPECT_TRUE(last.rows.empty());  // no contact at all is a valid snapshot
  const auto s = read_local_dump(text, "c.dump", {}, 200, "p.dump");
  EXPECT_EQ(s.timestep, 200);
  EXPECT_FALSE(s.vector);
  ASSERT_EQ(s.rows.size(), 2u);
  EXPECT_EQ(s.rows[0].id1, 2);
  EXPECT_EQ(s.rows[0].id2, 3);
  EXPECT_EQ(s.rows[0].force[0], 0.125);
  EXPECT_EQ(s.rows[0].line, 20);
  EXPECT_EQ(s.rows[1].force[0], 2.5e-3);
}

TEST(LocalDump, ReadsTheLiggghtsPairGranLocalLayout) {
  // compute pc all pair/gran/local pos id force: 6 positions, id1 id2 periodic flag, force.
  std::string columns;
  for (int k = 1; k <= 12; ++k) columns += (k > 1 ? " " : "") + ("c_pc[" + std::to_string(k) + "]");
  const auto text = local_snapshot(5000, columns, {"0 0 0 0 0 2e-3 4 9 0 1e-6 -2e-6 0.75"});
  LocalDumpColumns c;
  c.id1 = "c_pc[7]";
  c.id2 = "c_pc[8]";
  c.force = {"c_pc[10]", "c_pc[11]", "c_pc[12]"};
  const auto s = read_local_dump(text, "c.dump", c, 5000, "p.dump");
  EXPECT_TRUE(s.vector);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_EQ(s.rows[0].id1, 4);
  EXPECT_EQ(s.rows[0].id2, 9);
  EXPECT_EQ(s.rows[0].force, (Vec3{1e-6, -2e-6, 0.75}));
}

TEST(LocalDump, BadFilesNameLineAndColumn) {
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"1 2 -0.5"})),
            "c.dump:10:5: column fn: a normal force must be >= 0 N, got -0.5");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"1 2 0.5x"})),
            "c.dump:10:5: column fn: expected a finite number, got \"0.5x\"");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"1 2"})),
            "c.dump:10: expected 3 values (one per column), got 2");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"1.5 2 1"})),
            "c.dump:10:1: column id1: expected a particle id, got \"1.5\"");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"2 2 1"})),
            "c.dump:10: a contact of particle 2 with itself");
  EXPECT_EQ(local_error(local_snapshot(1, "a b fn", {"1 2 1"})),
            "c.dump:9: no column id1, id2 (columns: a b fn); name them with [[import]] "
            "contact_columns");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 f", {"1 2 1"})),
            "c.dump:9: no column fx, fy, fz (columns: id1 id2 f); name them with [[import]] "
            "contact_columns");
  auto short_text = local_snapshot(1, "id1 id2 fn", {"1 2 1", "2 3 1"});
  short_text.resize(short_text.size() - 6);  // drop the last entry
  EXPECT_EQ(local_error(short_text), "c.dump:11: the snapshot ends after 1 of 2 entries (NUMBER OF ENTRIES)");
  EXPECT_EQ(local_error(local_snapshot(1, "id1 id2 fn", {"1 2 1"}) + "3 4 1\n"),
            "c.dump:11: more entries than NUMBER OF ENTRIES (1)");
  EXPECT_EQ(local_error("id1 id2 fn\n1 2 3\n"), "c.dump: no \"ITEM: TIMESTEP\" line: not a LAMMPS local dump");
  EXPECT_EQ(local_error("ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x\n1 0\n"),
            "c.dump:5: a particle dump (ITEM: ATOMS), not a local dump (ITEM: ENTRIES): contacts "
            "names the file of `dump local`");
  // The particle dump's timestep must be there.
  EXPECT_EQ(local_error(local_snapshot(100, "id1 id2 fn", {}) + local_snapshot(200, "id1 id2 fn", {}),
                        {}, 150),
            "c.dump: no snapshot of timestep 150 (the one of p.dump); its timesteps: 100, 200");
}

// A scene file with its particle and contact dumps in a fresh folder.
class SceneContactImport : public ImportFolder {
 protected:
  // Three 1 mm spheres side by side (ids 7, 3, 5 from x = 10 mm), at timestep 400.
  std::string particles() const {
    return file("p.dump",
                "ITEM: TIMESTEP\n400\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 "
                "1\n0 1\nITEM: ATOMS id x y z radius\n"
                "5 0.014 0.005 0 0.001\n7 0.010 0.005 0 0.001\n3 0.012 0.005 0 0.001\n");
  }
  std::string scene(const TomlKeys& keys) const {
    return base_scene().add("import", with({{"file", particles()}, {"material", "steel"}}, keys));
  }
};

TEST_F(SceneContactImport, IdsMapToSceneParticlesAndTheNormalPartIsTaken) {
  // base_scene has particles 0 and 1; the import's rows are sorted by id: 3 (x = 12 mm) is
  // scene particle 2, 5 (x = 14 mm) is 3, 7 (x = 10 mm) is 4.
  const auto contacts = file("c.dump", local_snapshot(400, "id1 id2 fx fy fz",
                                                      {"3 7 -0.25 4e-3 0", "5 3 0.125 0 1e-3"}));
  const Scene s = load_scene_text(scene({{"contacts", contacts}}), "test.toml");
  const auto& f = s.imported_forces;
  ASSERT_EQ(f.pairs.size(), 2u);  // sorted by scene ids
  EXPECT_EQ(f.pairs[0].i, 2u);
  EXPECT_EQ(f.pairs[0].j, 3u);
  EXPECT_EQ(f.pairs[0].normal_force_N, 0.125);  // |F . n|, n along x
  EXPECT_EQ(f.pairs[1].i, 2u);
  EXPECT_EQ(f.pairs[1].j, 4u);
  EXPECT_EQ(f.pairs[1].normal_force_N, 0.25);
  // The vector (-0.25, 4e-3, 0) pushes id 7 (x = 10 mm) away from id 3 (x = 12 mm): it acts on
  // scene particle 4, so the force on particle 2 is its opposite, tangential part included.
  EXPECT_EQ(f.pairs[1].force_on_i_N, (Vec3{0.25, -4e-3, 0.0}));
  EXPECT_EQ(f.pairs[0].force_on_i_N, (Vec3{-0.125, 0.0, -1e-3}));  // id 5 pushes id 3 to -x
  ASSERT_EQ(f.wall_gap.size(), 5u);
  EXPECT_FALSE(f.imported(0));
  EXPECT_TRUE(f.imported(4));
  EXPECT_EQ(f.wall_gap[2], 1e-3);  // the default
  EXPECT_EQ(s.imports[0].contact_count, 2u);
  EXPECT_EQ(s.imports[0].contacts_timestep, 400);

  // Named columns, a scalar normal force.
  const auto named = file("n.dump", local_snapshot(400, "c_p[1] c_p[2] c_f", {"7 3 0.5"}));
  const Scene n = load_scene_text(
      scene({{"contacts", named}, {"wall_gap", 0.01},
             {"contact_columns", raw("{ id1 = \"c_p[1]\", id2 = \"c_p[2]\", normal_force = \"c_f\" }")}}),
      "test.toml");
  ASSERT_EQ(n.imported_forces.pairs.size(), 1u);
  EXPECT_EQ(n.imported_forces.pairs[0].normal_force_N, 0.5);
  EXPECT_EQ(n.imported_forces.wall_gap[3], 0.01);
}

TEST_F(SceneContactImport, ErrorsNameTheSceneKeyAndTheFilesLine) {
  const auto unknown = file("u.dump", local_snapshot(400, "id1 id2 fn", {"7 3 1", "7 8 1"}));
  expect_scene_error(scene({{"contacts", unknown}}),
                     {"test.toml:", "import[0].contacts: ", "u.dump:11: particle id 8 is not in ",
                      "p.dump"});
  const auto twice = file("t.dump", local_snapshot(400, "id1 id2 fn", {"7 3 1", "3 7 1"}));
  expect_scene_error(scene({{"contacts", twice}}),
                     {"t.dump:11: the contact of particles 3 and 7 is also on line 10"});
  const auto other_step = file("o.dump", local_snapshot(300, "id1 id2 fn", {}));
  expect_scene_error(scene({{"contacts", other_step}}),
                     {"o.dump: no snapshot of timestep 400 (the one of ", "p.dump); its timesteps: 300"});
  expect_scene_error(scene({{"contact_columns", raw("{ id1 = \"a\" }")}}),
                     {"import[0].contact_columns: goes with contacts"});
  expect_scene_error(scene({{"contacts", unknown}, {"contact_columns", raw("{ force = [\"a\"] }")}}),
                     {"force: expected 3 column names"});
  // A particle file without ids cannot be matched.
  const auto csv = file("p.csv", "x,y,z,radius\n0.010,0.005,0,0.001\n");
  expect_scene_error(std::string(base_scene().add("import", {{"file", csv}, {"material", "steel"}, {"contacts", unknown}})),
                     {"import[0].contacts: ", "p.csv: the particle file has no id column"});
  // Hertz without mechanics: refused unless every particle comes with its forces.
  const auto ok = file("ok.dump", local_snapshot(400, "id1 id2 fn", {"7 3 1"}));
  expect_scene_error(std::string(base_scene()
                                     .set("effects.mechanics", "off")
                                     .add("import", {{"file", particles()}, {"material", "steel"}, {"contacts", ok}})),
                     {"effects.mechanics: ", "import every particle with its forces"});
}

}  // namespace
}  // namespace tmdem::coupling::test
