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

}  // namespace

TEST(ResultWriterBatches, XdmfAlwaysListsTheStoredFramesAndFlushStoresTheRest) {
  const auto dir = std::filesystem::temp_directory_path() / ("tmdem-batches-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "r.h5").string();
  ResultHeader header;
  header.scene_toml = "format = \"tmdem-scene-1\"\n";
  header.radius_m = {1e-3, 1e-3};
  header.mass_kg = {1e-5, 1e-5};
  header.heat_capacity_J_per_K = {0.01, 0.01};
  header.material = {0, 0};
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
