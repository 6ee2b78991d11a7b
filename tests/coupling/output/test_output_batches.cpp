// ResultWriter past its first 32 frames: frames wait in memory and reach the .h5 together
// with the XDMF rewrite, so the XDMF always lists what the .h5 holds; flush() and finish()
// store what waits, with the contacts of the waiting frames in their places.
#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "coupling/output/PendingFrame.h"
#include "coupling/output/ResultWriter.h"
#include "support/TempDir.h"

namespace {

using tmdem::coupling::PendingFrame;
using tmdem::coupling::ResultHeader;
using tmdem::coupling::ResultWriter;

std::size_t frames_listed(const std::string& xdmf_path) {
  std::ifstream in(xdmf_path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::size_t n = 0;
  for (auto at = s.find("<Grid Name=\"particles\" GridType=\"Uniform\""); at != std::string::npos; at = s.find("<Grid Name=\"particles\" GridType=\"Uniform\"", at + 1)) ++n;
  return n;
}

// Frame f of two particles at t = f s: one contact (0, 1) in every third frame, force f N.
PendingFrame frame(std::size_t f) {
  PendingFrame s;
  s.time_s = double(f);
  s.position_m = {double(f), 0, 0, double(f) + 1, 0, 0};
  s.velocity_m_per_s.assign(6, 0.0);
  s.temperature_K = {300.0 + double(f), 301.0 + double(f)};
  if (f % 3 == 0) s.contact_pair = {0, 1}, s.normal_force_N = {double(f)}, s.conductance_W_per_K = {1e-3};
  return s;
}

// The header of the two particles of frame().
ResultHeader two_particle_header() {
  ResultHeader header;
  header.scene_toml = "format = \"tmdem-scene-1\"\n";
  header.radius_m = {1e-3, 1e-3};
  header.mass_kg = {1e-5, 1e-5};
  header.heat_capacity_J_per_K = {0.01, 0.01};
  header.material = {0, 0};
  return header;
}

}  // namespace

TEST(ResultWriterBatches, XdmfAlwaysListsTheStoredFramesAndFlushStoresTheRest) {
  const auto dir = std::filesystem::temp_directory_path() / ("tmdem-batches-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "r.h5").string();
  const ResultHeader header = two_particle_header();
  const std::size_t total = 1100;
  {
    ResultWriter writer(path, header, true);
    bool waited = false;
    for (std::size_t f = 0; f < total; ++f) {
      writer.write_frame(frame(f).view());
      ASSERT_EQ(writer.frames(), f + 1);
      if (f < 32) {
        ASSERT_EQ(writer.stored_frames(), f + 1) << "one by one up to 32 frames";
      }
      // A batch is due once 1/32 of the frames wait (or a second has passed).
      ASSERT_LT(32 * (writer.frames() - writer.stored_frames()), writer.frames()) << f;
      waited = waited || writer.stored_frames() < writer.frames();
      if (f % 50 == 0 || f + 1 == total) {
        ASSERT_EQ(frames_listed(writer.xdmf_path()), writer.stored_frames()) << f;
      }
    }
    EXPECT_TRUE(waited) << "past 32 frames some frames wait for their batch";
    writer.flush();
    EXPECT_EQ(writer.stored_frames(), total);
    EXPECT_EQ(frames_listed(writer.xdmf_path()), total);
    for (std::size_t f = total; f < total + 5; ++f) writer.write_frame(frame(f).view());
    writer.finish("ok");  // stores the 5 frames written after the flush
  }
  EXPECT_EQ(frames_listed((dir / "r.xdmf").string()), total + 5);
  H5::H5File file(path, H5F_ACC_RDONLY);
  H5::DataSet time = file.openDataSet("/frames/time");
  hsize_t frames = 0;
  time.getSpace().getSimpleExtentDims(&frames);
  ASSERT_EQ(frames, total + 5);
  std::vector<double> t(frames);
  time.read(t.data(), H5::PredType::NATIVE_DOUBLE);
  std::vector<long long> offset(frames + 1);
  file.openDataSet("/frames/contact_offset").read(offset.data(), H5::PredType::NATIVE_LLONG);
  std::vector<double> force(std::size_t(offset.back()));
  file.openDataSet("/contacts/normal_force").read(force.data(), H5::PredType::NATIVE_DOUBLE);
  for (std::size_t f = 0; f < frames; ++f) {
    ASSERT_EQ(t[f], double(f));
    ASSERT_EQ(offset[f + 1] - offset[f], f % 3 == 0 ? 1 : 0) << f;
    if (f % 3 == 0) {
      ASSERT_EQ(force[std::size_t(offset[f])], double(f)) << f;
    }
  }
  std::filesystem::remove_all(dir);
}

namespace {

// File address of the first chunk of `dataset` in the result file at `path`, and its filters.
std::pair<haddr_t, int> first_chunk(const std::string& path, const char* dataset) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(d);
  const int filters = H5Pget_nfilters(plist);
  const hsize_t origin[1] = {0};
  unsigned mask = 0;
  haddr_t address = HADDR_UNDEF;
  hsize_t size = 0;
  H5Dget_chunk_info_by_coord(d, origin, &mask, &address, &size);
  H5Pclose(plist);
  H5Dclose(d);
  H5Fclose(file);
  return {address, filters};
}

}  // namespace

// The [F] datasets (one row per frame) get a row in their last chunk with every frame. They are
// unfiltered, so that chunk keeps its place: a run killed while rewriting it leaves the rows of
// earlier frames as they were, for the restart from the last checkpoint (a compressed chunk
// moved on each rewrite, and a SIGKILL once left /frames/time unreadable).
TEST(ResultWriterBatches, PerFrameRowsAreRewrittenInPlace) {
  const tmdem::test::TempDir dir;
  const std::string path = dir.file("r.h5");
  const ResultHeader header = two_particle_header();
  {
    ResultWriter writer(path, header, true);
    for (std::size_t f = 0; f < 10; ++f) writer.write_frame(frame(f).view());
    writer.finish("ok");
  }
  const char* per_frame[] = {"/frames/time", "/frames/thermal_energy", "/frames/boundary_heat",
                             "/frames/contact_offset"};
  std::vector<haddr_t> before;
  for (const char* d : per_frame) {
    const auto [address, filters] = first_chunk(path, d);
    EXPECT_EQ(filters, 0) << d;
    EXPECT_NE(address, HADDR_UNDEF) << d;
    before.push_back(address);
  }
  {
    ResultWriter writer = ResultWriter::reopen(path, 10);
    for (std::size_t f = 10; f < 40; ++f) writer.write_frame(frame(f).view());
    writer.finish("ok");
  }
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_EQ(first_chunk(path, per_frame[i]).first, before[i]) << per_frame[i];
}

namespace {

// Overwrites the bytes of the first chunk of `dataset` with 0xff, as a crash in the middle of
// its rewrite may leave them.
void garble_first_chunk(const std::string& path, const char* dataset) {
  haddr_t address = HADDR_UNDEF;
  hsize_t size = 0;
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const hsize_t origin[2] = {0, 0};
    unsigned mask = 0;
    H5Dget_chunk_info_by_coord(d, origin, &mask, &address, &size);
    H5Dclose(d);
    H5Fclose(file);
  }
  ASSERT_NE(address, HADDR_UNDEF) << dataset;
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(std::streamoff(address));
  const std::string garbage(size, '\xff');
  f.write(garbage.data(), std::streamsize(size));
}

}  // namespace

// A crash while the contacts' last chunk was rewritten can leave its rows unreadable. The
// checkpoint's copy of that chunk (ResultWriter::contact_tail) is written again by the restart:
// here the chunk is garbled by hand after the checkpoint, and the restarted file holds every
// contact as written.
TEST(ResultWriterBatches, RestartWritesTheContactsLastChunkAgainFromTheCheckpoint) {
  const tmdem::test::TempDir dir;
  const std::string path = dir.file("r.h5");
  const ResultHeader header = two_particle_header();
  tmdem::coupling::ContactTail tail;
  {
    ResultWriter writer(path, header, true);
    for (std::size_t f = 0; f < 10; ++f) writer.write_frame(frame(f).view());
    writer.flush();
    tail = writer.contact_tail();
    writer.finish("ok");
  }
  EXPECT_EQ(tail.start, 0);
  EXPECT_EQ(tail.rows, 4);  // frames 0, 3, 6 and 9 have a contact
  ASSERT_EQ(tail.normal_force_N.size(), 4u);
  for (const char* d : {"/contacts/normal_force", "/contacts/pair"}) garble_first_chunk(path, d);
  {
    H5::H5File file(path, H5F_ACC_RDONLY);
    std::vector<double> force(4);
    EXPECT_ANY_THROW(file.openDataSet("/contacts/normal_force").read(force.data(), H5::PredType::NATIVE_DOUBLE))
        << "the garbled chunk must be unreadable for this test to mean anything";
  }
  tmdem::coupling::RestartMatch match;
  match.particles = 2;
  match.scene_toml = header.scene_toml;
  match.checkpoint_time_s = 9.0;
  match.contact_tail = &tail;
  {
    ResultWriter writer = ResultWriter::reopen(path, 10, &match);
    for (std::size_t f = 10; f < 20; ++f) writer.write_frame(frame(f).view());
    writer.finish("ok");
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  std::vector<long long> offset(21), pair(2 * 7);
  file.openDataSet("/frames/contact_offset").read(offset.data(), H5::PredType::NATIVE_LLONG);
  ASSERT_EQ(offset.back(), 7);
  std::vector<double> force(7);
  file.openDataSet("/contacts/normal_force").read(force.data(), H5::PredType::NATIVE_DOUBLE);
  file.openDataSet("/contacts/pair").read(pair.data(), H5::PredType::NATIVE_LLONG);
  for (std::size_t f = 0; f < 20; ++f) {
    ASSERT_EQ(offset[f + 1] - offset[f], f % 3 == 0 ? 1 : 0) << f;
    if (f % 3 != 0) continue;
    const auto row = std::size_t(offset[f]);
    EXPECT_EQ(force[row], double(f)) << f;
    EXPECT_EQ(pair[2 * row], 0) << f;
    EXPECT_EQ(pair[2 * row + 1], 1) << f;
  }
}
