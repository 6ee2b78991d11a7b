// Checkpoint: round trip, and written whole or not at all.
#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "coupling/output/Checkpoint.h"
#include "support/TempDir.h"

namespace {

namespace fs = std::filesystem;
using tmdem::coupling::CheckpointState;
using tmdem::coupling::OutputError;
using tmdem::test::TempDir;

CheckpointState sample_checkpoint() {
  CheckpointState s;
  s.time_s = 12.5;
  s.position_m = {0, 1e-3, 0, 2e-3, 1e-3, 0, 1e-3, 2.7e-3, 0};
  s.velocity_m_per_s = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  s.angular_velocity_rad_per_s = {-1, -2, -3, -4, -5, -6, -7, -8, -9};
  s.temperature_K = {373.15, 300.0, 293.15};
  s.boundary_heat_J = 4.25;
  s.scene_toml = "format = \"tmdem-scene-1\"\n[simulation]\nduration = 100.0\n";
  s.frames_written = 126;
  s.contact_pair = {0, 1, 1, 2, 0, -1};
  s.contact_impulse_N_s = {1e-3, 0, 0, 2e-3, 1e-5, 0, 3e-3, 0, -1e-5};
  s.contact_tangential_force_N = {0.1, -0.2, 0.3, 0, 0, 0, -1.5, 2.5, 1e-9};
  s.extra = {{"mechanics.step", 12500.0}, {"next_frame_time_s", 12.6}};
  return s;
}

void expect_equal(const CheckpointState& a, const CheckpointState& b) {
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.position_m, b.position_m);
  EXPECT_EQ(a.velocity_m_per_s, b.velocity_m_per_s);
  EXPECT_EQ(a.angular_velocity_rad_per_s, b.angular_velocity_rad_per_s);
  EXPECT_EQ(a.temperature_K, b.temperature_K);
  EXPECT_EQ(a.boundary_heat_J, b.boundary_heat_J);
  EXPECT_EQ(a.scene_toml, b.scene_toml);
  EXPECT_EQ(a.frames_written, b.frames_written);
  EXPECT_EQ(a.contact_pair, b.contact_pair);
  EXPECT_EQ(a.contact_impulse_N_s, b.contact_impulse_N_s);
  EXPECT_EQ(a.contact_tangential_force_N, b.contact_tangential_force_N);
  EXPECT_EQ(a.extra, b.extra);
  EXPECT_EQ(a.contact_normal_force_N, b.contact_normal_force_N);
  EXPECT_EQ(a.has_mechanics, b.has_mechanics);
  EXPECT_EQ(a.detector_margin_m, b.detector_margin_m);
  EXPECT_EQ(a.detector_wall_margin_m, b.detector_wall_margin_m);
  EXPECT_EQ(a.detector_rebuilds, b.detector_rebuilds);
  EXPECT_EQ(a.detector_reference_position_m, b.detector_reference_position_m);
  EXPECT_EQ(a.candidate_pair, b.candidate_pair);
  EXPECT_EQ(a.candidate_force_N, b.candidate_force_N);
  EXPECT_EQ(a.candidate_rolling_torque_Nm, b.candidate_rolling_torque_Nm);
  EXPECT_EQ(a.candidate_held_overlap_m, b.candidate_held_overlap_m);
  EXPECT_EQ(a.contact_solver_state, b.contact_solver_state);
  EXPECT_EQ(a.thermal_pattern_pair, b.thermal_pattern_pair);
  EXPECT_EQ(a.result_contact_tail.start, b.result_contact_tail.start);
  EXPECT_EQ(a.result_contact_tail.rows, b.result_contact_tail.rows);
  EXPECT_EQ(a.result_contact_tail.pair, b.result_contact_tail.pair);
  EXPECT_EQ(a.result_contact_tail.normal_force_N, b.result_contact_tail.normal_force_N);
  EXPECT_EQ(a.result_contact_tail.tangential_force_N, b.result_contact_tail.tangential_force_N);
  EXPECT_EQ(a.result_contact_tail.conductance_W_per_K, b.result_contact_tail.conductance_W_per_K);
  EXPECT_EQ(a.result_contact_tail.heat_flow_W, b.result_contact_tail.heat_flow_W);
}

// sample_checkpoint() plus what a bitwise restart of a moving packing needs.
CheckpointState sample_with_mechanics() {
  CheckpointState s = sample_checkpoint();
  s.contact_normal_force_N = {0.1 / 3.0, 2e-3, 1e300};
  s.has_mechanics = true;
  s.detector_margin_m = 1.0 / 3.0 * 1e-4;
  s.detector_wall_margin_m = 2.0 / 3.0 * 1e-3;
  s.detector_rebuilds = 4096;
  s.detector_reference_position_m = {1, 2, 3, 4, 5, 6, 7, 8, 9.000000000000002};
  s.candidate_pair = {0, -2, 0, -1, 0, 1, 0, 2, 1, 2};
  s.candidate_force_N = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, -1e-300};
  s.candidate_rolling_torque_Nm = {0, 0, 0, 1e-9, 0, -2e-9, 0, 0, 0, 0, 0, 0, 3.0 / 7.0, 1e-300, 0};
  s.candidate_held_overlap_m = {0, 1.25e-4, 0, 3.0 / 7.0 * 1e-5, 1e-300};
  s.thermal_pattern_pair = {0, -1, 0, 1, 1, 2};
  s.contact_solver_state = {1.7976931348623157e308 / 3.0};
  // The result file's contacts in their last chunk: rows 256 and 257 (frozen pairs and forces
  // stored as block series leave their vectors empty).
  s.result_contact_tail.start = 256;
  s.result_contact_tail.rows = 258;
  s.result_contact_tail.heat_flow_W = {1.0 / 3.0, -2e-300};
  return s;
}

TEST(Checkpoint, RoundTrip) {
  TempDir dir;
  const std::string path = dir.file("run.ckpt.h5");
  write_checkpoint(path, sample_checkpoint());
  expect_equal(tmdem::coupling::read_checkpoint(path), sample_checkpoint());
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(dir.entries(), 1u);

  H5::H5File file(path, H5F_ACC_RDONLY);
  H5::Attribute format = file.openAttribute("format");
  std::string text;
  format.read(format.getStrType(), text);
  EXPECT_EQ(text, "tmdem-checkpoint-1");
}

TEST(Checkpoint, RoundTripWithoutContacts) {
  TempDir dir;
  CheckpointState s = sample_checkpoint();
  s.contact_pair.clear();
  s.contact_impulse_N_s.clear();
  s.contact_tangential_force_N.clear();
  s.extra.clear();
  write_checkpoint(dir.file("c.h5"), s);
  expect_equal(tmdem::coupling::read_checkpoint(dir.file("c.h5")), s);
}

// Every double bit for bit, the mechanics group and the thermal pattern included; a file
// without them (the older layout) reads with has_mechanics false and no pattern.
TEST(Checkpoint, RoundTripWithMechanicsStateAndPattern) {
  TempDir dir;
  write_checkpoint(dir.file("m.h5"), sample_with_mechanics());
  expect_equal(tmdem::coupling::read_checkpoint(dir.file("m.h5")), sample_with_mechanics());
  write_checkpoint(dir.file("o.h5"), sample_checkpoint());
  const CheckpointState older = tmdem::coupling::read_checkpoint(dir.file("o.h5"));
  EXPECT_FALSE(older.has_mechanics);
  EXPECT_TRUE(older.contact_normal_force_N.empty());
  EXPECT_TRUE(older.thermal_pattern_pair.empty());
  EXPECT_TRUE(older.result_contact_tail.empty());
}

TEST(Checkpoint, RejectsMechanicsStateOfOtherSizes) {
  TempDir dir;
  CheckpointState s = sample_with_mechanics();
  s.candidate_force_N.pop_back();
  EXPECT_THROW(write_checkpoint(dir.file("a.h5"), s), std::invalid_argument);
  s = sample_with_mechanics();
  s.detector_reference_position_m.resize(6);  // 2 particles' worth for 3 particles
  EXPECT_THROW(write_checkpoint(dir.file("b.h5"), s), std::invalid_argument);
  s = sample_with_mechanics();
  s.contact_normal_force_N.push_back(1.0);
  EXPECT_THROW(write_checkpoint(dir.file("c.h5"), s), std::invalid_argument);
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(Checkpoint, OverwriteReplacesWhole) {
  TempDir dir;
  const std::string path = dir.file("c.h5");
  write_checkpoint(path, sample_checkpoint());
  CheckpointState later = sample_checkpoint();
  later.time_s = 20.0;
  later.temperature_K = {1.0, 2.0, 3.0};
  write_checkpoint(path, later);
  expect_equal(tmdem::coupling::read_checkpoint(path), later);
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(Checkpoint, MissingFolderLeavesNoFileAndNamesThePath) {
  TempDir dir;
  const std::string path = dir.file("missing/c.h5");
  try {
    write_checkpoint(path, sample_checkpoint());
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(Checkpoint, FailedWriteKeepsThePreviousCheckpoint) {
  TempDir dir;
  const std::string path = dir.file("c.h5");
  write_checkpoint(path, sample_checkpoint());
  fs::create_directory(path + ".tmp");  // the temporary file cannot be created
  CheckpointState later = sample_checkpoint();
  later.time_s = 99.0;
  EXPECT_THROW(write_checkpoint(path, later), OutputError);
  expect_equal(tmdem::coupling::read_checkpoint(path), sample_checkpoint());
  EXPECT_TRUE(fs::is_directory(path + ".tmp"));  // not ours: left alone
}

TEST(Checkpoint, RejectsInconsistentState) {
  TempDir dir;
  CheckpointState s = sample_checkpoint();
  s.velocity_m_per_s.pop_back();
  EXPECT_THROW(write_checkpoint(dir.file("c.h5"), s), std::invalid_argument);
  s = sample_checkpoint();
  s.contact_impulse_N_s.pop_back();
  EXPECT_THROW(write_checkpoint(dir.file("c.h5"), s), std::invalid_argument);
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(Checkpoint, ReadRejectsMissingAndForeignFiles) {
  TempDir dir;
  EXPECT_THROW(tmdem::coupling::read_checkpoint(dir.file("none.h5")), OutputError);
  {
    H5::H5File other(dir.file("other.h5"), H5F_ACC_TRUNC);
  }
  try {
    tmdem::coupling::read_checkpoint(dir.file("other.h5"));
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("other.h5")), std::string::npos) << e.what();
  }
}

}  // namespace
