// /probes of the result file (coupling/output/ResultProbes.h): per frame and probe the count,
// mean, min and max temperature of the particles whose centre lies inside, computed from the
// frame the writer stores; a probe holding no particle gives count 0 and 0 K; a reopened file
// (restart) is cut back with the frames and continues with the same rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "coupling/output/Hdf5Io.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/PendingFrame.h"
#include "coupling/output/ResultProbes.h"
#include "coupling/output/ResultWriter.h"
#include "tests/coupling/output/ScratchResultFile.h"
#include "tests/coupling/output/ThreeParticleHeader.h"

namespace tmdem::coupling::test {
namespace {

// Three particles on the x axis at 0, 2 and 5 mm; particle i at 300 + 10 i + f K in frame f,
// except particle 1, which cools by 3 K per frame (so min and max change places over the run).
PendingFrame probe_frame(std::size_t f) {
  PendingFrame s;
  s.time_s = 0.5 * double(f);
  s.position_m = {0.0, 0.0, 0.0, 0.002, 0.0, 0.0, 0.005, 0.0, 0.0};
  s.velocity_m_per_s.assign(9, 0.0);
  s.temperature_K = {300.0 + double(f), 310.0 - 3.0 * double(f), 320.0 + double(f)};
  return s;
}

// "near": sphere of 2 mm around the origin (particles 0 and 1, the second on its boundary);
// "far": box of 2 x 1 x 1 mm around x = 5 mm (particle 2); "empty": a sphere holding none.
ResultHeader probe_header() {
  ResultHeader header = three_particle_header();
  header.scene_toml = "format = \"tmdem-scene-1\"\n";
  header.probes = {{"near", {0.0, 0.0, 0.0}, 0.002, {}},
                   {"far", {0.005, 0.0, 0.0}, 0.0, {0.002, 0.001, 0.001}},
                   {"empty", {0.0, 0.01, 0.0}, 0.001, {}}};
  return header;
}

// Every frame's readings checked against the per-particle temperatures stored in the same file.
void expect_readings_match_stored_temperatures(const std::string& path, std::size_t frames) {
  bool has_probes = false;
  const ProbeSeries s = read_probe_series(path, has_probes);
  ASSERT_TRUE(has_probes);
  ASSERT_EQ(s.names, (std::vector<std::string>{"near", "far", "empty"}));
  ASSERT_EQ(s.time_s.size(), frames);
  Hdf5Handle file = hdf5::open_file(path, false, false);
  const std::vector<double> T = hdf5::read_double_array(file.get(), "/frames/temperature", 3);
  ASSERT_EQ(T.size(), 3 * frames);
  for (std::size_t f = 0; f < frames; ++f) {
    const double* t = &T[3 * f];
    EXPECT_EQ(s.time_s[f], 0.5 * double(f));
    // near: particles 0 and 1.
    EXPECT_EQ(s.count[3 * f + 0], 2);
    EXPECT_DOUBLE_EQ(s.mean_K[3 * f + 0], 0.5 * (t[0] + t[1]));
    EXPECT_EQ(s.min_K[3 * f + 0], std::min(t[0], t[1]));
    EXPECT_EQ(s.max_K[3 * f + 0], std::max(t[0], t[1]));
    // far: particle 2 alone.
    EXPECT_EQ(s.count[3 * f + 1], 1);
    EXPECT_EQ(s.mean_K[3 * f + 1], t[2]);
    EXPECT_EQ(s.min_K[3 * f + 1], t[2]);
    EXPECT_EQ(s.max_K[3 * f + 1], t[2]);
    // empty: count 0 and 0 K, never NaN.
    EXPECT_EQ(s.count[3 * f + 2], 0);
    EXPECT_EQ(s.mean_K[3 * f + 2], 0.0);
    EXPECT_EQ(s.min_K[3 * f + 2], 0.0);
    EXPECT_EQ(s.max_K[3 * f + 2], 0.0);
  }
  // The hand-computed values of frame 4: 304, 298 and 324 K.
  if (frames > 4) {
    EXPECT_DOUBLE_EQ(s.mean_K[12], 301.0);
    EXPECT_EQ(s.min_K[12], 298.0);
    EXPECT_EQ(s.max_K[12], 304.0);
    EXPECT_EQ(s.mean_K[13], 324.0);
  }
}

}  // namespace

TEST(ResultProbes, ContainmentIncludesTheBoundary) {
  const ProbeRegion sphere{"s", {0.0, 0.0, 0.0}, 1.0, {}};
  const ProbeRegion box{"b", {0.0, 0.0, 0.0}, 0.0, {2.0, 4.0, 6.0}};
  const double on_sphere[3] = {0.0, 1.0, 0.0}, outside_sphere[3] = {0.8, 0.8, 0.0};
  EXPECT_TRUE(probe_contains(sphere, on_sphere));
  EXPECT_FALSE(probe_contains(sphere, outside_sphere));
  const double corner[3] = {1.0, -2.0, 3.0}, past_z[3] = {0.0, 0.0, 3.0001};
  EXPECT_TRUE(probe_contains(box, corner));
  EXPECT_FALSE(probe_contains(box, past_z));
}

TEST(ResultProbes, EveryFrameHoldsCountMeanMinMaxOfTheParticlesInside) {
  ScratchResultFile scratch("probes");
  {
    ResultWriter writer(scratch.path, probe_header(), false);
    for (std::size_t f = 0; f < 6; ++f) writer.write_frame(probe_frame(f).view());
    writer.finish("ok");
  }
  expect_readings_match_stored_temperatures(scratch.path, 6);
  Hdf5Handle file = hdf5::open_file(scratch.path, false, false);
  EXPECT_EQ(hdf5::read_double_array(file.get(), "/probes/radius", 0),
            (std::vector<double>{0.002, 0.0, 0.001}));
  std::string units;
  Hdf5Handle mean = hdf5::open_dataset(file.get(), "/probes/mean_K");
  ASSERT_TRUE(hdf5::read_string_attribute(mean.get(), "units", units));
  EXPECT_EQ(units, "K");
}

TEST(ResultProbes, ReopenCutsTheRowsBackWithTheFramesAndContinuesAlike) {
  ScratchResultFile straight("probes-straight");
  ScratchResultFile restarted("probes-restarted");
  {
    ResultWriter writer(straight.path, probe_header(), false);
    for (std::size_t f = 0; f < 8; ++f) writer.write_frame(probe_frame(f).view());
    writer.finish("ok");
  }
  {
    ResultWriter writer(restarted.path, probe_header(), false);
    for (std::size_t f = 0; f < 6; ++f) writer.write_frame(probe_frame(f).view());
    writer.finish("interrupted");
  }
  {
    ResultWriter writer = ResultWriter::reopen(restarted.path, 3);
    for (std::size_t f = 3; f < 8; ++f) writer.write_frame(probe_frame(f).view());
    writer.finish("ok");
  }
  expect_readings_match_stored_temperatures(restarted.path, 8);
  bool a = false, b = false;
  const ProbeSeries x = read_probe_series(straight.path, a), y = read_probe_series(restarted.path, b);
  EXPECT_EQ(x.count, y.count);
  EXPECT_EQ(x.mean_K, y.mean_K);
  EXPECT_EQ(x.min_K, y.min_K);
  EXPECT_EQ(x.max_K, y.max_K);
}

TEST(ResultProbes, AFileWithoutProbesHasNoGroup) {
  ScratchResultFile scratch("no-probes");
  {
    ResultHeader header = three_particle_header();
    ResultWriter writer(scratch.path, header, false);
    writer.write_frame(probe_frame(0).view());
    writer.finish("ok");
  }
  bool has_probes = true;
  const ProbeSeries s = read_probe_series(scratch.path, has_probes);
  EXPECT_FALSE(has_probes);
  EXPECT_TRUE(s.names.empty());
  EXPECT_THROW(read_probe_series(scratch.path + ".missing", has_probes), OutputError);
}

}  // namespace tmdem::coupling::test
