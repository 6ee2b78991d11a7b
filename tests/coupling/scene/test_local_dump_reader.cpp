// [[import]] contacts: the LAMMPS / LIGGGHTS local dump reader gives the file's exact values of
// the snapshot matching the particle dump (else the last); bad files are refused naming
// FILE:LINE(:COLUMN).
#include <gtest/gtest.h>

#include "coupling/scene/LocalDumpReader.h"
#include "coupling/scene/PackingFile.h"
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

}  // namespace
}  // namespace tmdem::coupling::test
