// A frozen bed (ResultHeader::frozen, settle runs): positions, velocities and the contacts'
// pair, forces and conductance are written once as blocks (BlockSeries.h) and every later frame
// is a hard link while the values stay the same; a changed block is written anew. Readers of
// the contract paths see every frame's values, as in a file without blocks; the XDMF views are
// the blocks themselves; a restart cuts the blocks back and links the next frame again.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/output/Hdf5Io.h"
#include "coupling/output/ResultWriter.h"
#include "ScratchResultFile.h"
#include "ThreeParticleHeader.h"

namespace {

namespace fs = std::filesystem;
using namespace tmdem::coupling;

struct FrozenFile : test::ScratchResultFile {
  FrozenFile() : ScratchResultFile("frozen") {}
};

constexpr std::size_t kN = 3, kC = 2, kFrames = 6;

ResultHeader frozen_header() {
  ResultHeader header = test::three_particle_header();
  WallPlane floor;
  floor.normal = {0.0, 1.0, 0.0};
  header.walls = {floor};
  header.frozen = true;
  header.frozen_contacts = kC;
  return header;
}

// Frame f of a frozen bed: the same positions, zero velocities, the same two contacts (0, 1)
// and (0, floor) and forces; temperatures and heat flows change every frame, the conductance
// from frame 4 on (as with a temperature-dependent conductivity).
struct FrozenFrame {
  std::vector<double> x{0.0, 1e-3, 0.0, 2e-3, 1e-3, 0.0, 5e-3, 2e-3, 0.0};
  std::vector<double> v = std::vector<double>(3 * kN, 0.0);
  std::vector<double> T, force{2.5, 7.0}, H, tangential{0.1, 0.0, -0.2, 0.0, 0.3, 0.0}, Q;
  std::vector<std::int64_t> pair{0, 1, 0, -1};
  explicit FrozenFrame(std::size_t f) {
    T = {300.0 + 10.0 * double(f), 301.0, 302.0 - double(f)};
    H = f >= 4 ? std::vector<double>{0.02, 0.05} : std::vector<double>{0.01, 0.04};
    Q = {-0.5 - double(f), 1.0 + double(f)};
  }
  FrameView view(double t) const { return FrameView{t, x, v, T, 1.0, 0.0, pair, force, H, tangential, Q, {}}; }
};

void write_frames(ResultWriter& writer, std::size_t from, std::size_t to) {
  for (std::size_t f = from; f < to; ++f) {
    const FrozenFrame frame(f);
    writer.write_frame(frame.view(double(f)));
  }
}

// The object a link leads to (equal for hard links to one object).
haddr_t object_of(hid_t file, const std::string& path) {
  H5O_info_t info;
  hdf5::check_ok(H5Oget_info_by_name(file, path.c_str(), &info, H5P_DEFAULT),  // 1.10 API
                 path);
  return info.addr;
}

template <class T>
std::vector<T> read_all(hid_t file, const std::string& path, hid_t memory_type,
                        std::vector<hsize_t>& dims) {
  Hdf5Handle d = hdf5::open_dataset(file, path.c_str());
  dims = hdf5::dataset_dims(d.get());
  std::size_t values = 1;
  for (hsize_t n : dims) values *= n;
  std::vector<T> out(values);
  hdf5::read_rows(d.get(), 0, dims[0], out.data(), memory_type);
  return out;
}

// Every contract dataset reads as if each frame had been written in full.
void expect_every_frame(hid_t file, std::size_t frames) {
  std::vector<hsize_t> dims;
  const auto x = read_all<double>(file, "/frames/position", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{frames, kN, 3}));
  const auto v = read_all<double>(file, "/frames/velocity", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{frames, kN, 3}));
  const auto T = read_all<double>(file, "/frames/temperature", H5T_NATIVE_DOUBLE, dims);
  const auto pair = read_all<std::int64_t>(file, "/contacts/pair", H5T_NATIVE_INT64, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{frames * kC, 2}));
  const auto force = read_all<double>(file, "/contacts/normal_force", H5T_NATIVE_DOUBLE, dims);
  const auto H = read_all<double>(file, "/contacts/conductance", H5T_NATIVE_DOUBLE, dims);
  const auto tangential =
      read_all<double>(file, "/contacts/tangential_force", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{frames * kC, 3}));
  const auto Q = read_all<double>(file, "/contacts/heat_flow", H5T_NATIVE_DOUBLE, dims);
  const auto offset = read_all<std::int64_t>(file, "/frames/contact_offset", H5T_NATIVE_INT64, dims);
  for (std::size_t f = 0; f < frames; ++f) {
    const FrozenFrame want(f);
    EXPECT_EQ(offset[f], std::int64_t(f * kC));
    for (std::size_t k = 0; k < 3 * kN; ++k) {
      EXPECT_EQ(x[3 * kN * f + k], want.x[k]) << "frame " << f;
      EXPECT_EQ(v[3 * kN * f + k], 0.0) << "frame " << f;
    }
    for (std::size_t i = 0; i < kN; ++i) EXPECT_EQ(T[kN * f + i], want.T[i]) << "frame " << f;
    for (std::size_t c = 0; c < kC; ++c) {
      const std::size_t row = kC * f + c;
      EXPECT_EQ(pair[2 * row], want.pair[2 * c]);
      EXPECT_EQ(pair[2 * row + 1], want.pair[2 * c + 1]);
      EXPECT_EQ(force[row], want.force[c]);
      EXPECT_EQ(H[row], want.H[c]) << "frame " << f;
      EXPECT_EQ(Q[row], want.Q[c]) << "frame " << f;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(tangential[3 * row + k], want.tangential[3 * c + k]);
    }
  }
}

}  // namespace

TEST(FrozenBed, GeometryAndContactsAreWrittenOnceAndReadInEveryFrame) {
  FrozenFile dir;
  {
    ResultWriter writer(dir.path, frozen_header(), true);
    write_frames(writer, 0, kFrames);
    writer.finish("ok");
  }
  Hdf5Handle file = hdf5::open_file(dir.path, false, false);
  expect_every_frame(file.get(), kFrames);
  const hid_t h = file.get();
  // One object for every frame's positions, velocities, pairs and forces.
  for (std::size_t f = 1; f < kFrames; ++f) {
    const std::string k = std::to_string(f);
    EXPECT_EQ(object_of(h, "/frames/blocks/position_" + k), object_of(h, "/frames/blocks/position_0"));
    EXPECT_EQ(object_of(h, "/frames/blocks/velocity_" + k), object_of(h, "/frames/blocks/velocity_0"));
    EXPECT_EQ(object_of(h, "/contacts/blocks/pair_" + k), object_of(h, "/contacts/blocks/pair_0"));
    EXPECT_EQ(object_of(h, "/contacts/blocks/normal_force_" + k),
              object_of(h, "/contacts/blocks/normal_force_0"));
    // The XDMF views are those blocks.
    EXPECT_EQ(object_of(h, "/xdmf/frame_" + k + "/position"), object_of(h, "/frames/blocks/position_0"));
    EXPECT_EQ(object_of(h, "/xdmf/frame_" + k + "/normal_force"),
              object_of(h, "/contacts/blocks/normal_force_0"));
  }
  // The conductance changed at frame 4: a second object, linked by frame 5.
  EXPECT_EQ(object_of(h, "/contacts/blocks/conductance_3"), object_of(h, "/contacts/blocks/conductance_0"));
  EXPECT_NE(object_of(h, "/contacts/blocks/conductance_4"), object_of(h, "/contacts/blocks/conductance_0"));
  EXPECT_EQ(object_of(h, "/contacts/blocks/conductance_5"), object_of(h, "/contacts/blocks/conductance_4"));
  EXPECT_EQ(object_of(h, "/xdmf/frame_5/conductance"), object_of(h, "/contacts/blocks/conductance_4"));
  // The views' contact end points start with the frame's positions.
  std::vector<hsize_t> dims;
  const auto points = read_all<double>(h, "/xdmf/frame_2/contact_points", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{kN + 1, 3}));  // + the foot of the floor contact
  for (std::size_t k = 0; k < 3 * kN; ++k) EXPECT_EQ(points[k], FrozenFrame(2).x[k]);
  EXPECT_EQ(points[3 * kN + 1], 0.0);  // on the floor y = 0
}

TEST(FrozenBed, RestartCutsTheBlocksBackAndLinksTheNextFrameAgain) {
  FrozenFile dir;
  {
    ResultWriter writer(dir.path, frozen_header(), true);
    write_frames(writer, 0, kFrames);
    writer.finish("ok");
  }
  {
    ResultWriter writer = ResultWriter::reopen(dir.path, 3);
    write_frames(writer, 3, kFrames);
    writer.finish("ok");
  }
  Hdf5Handle file = hdf5::open_file(dir.path, false, false);
  expect_every_frame(file.get(), kFrames);
  EXPECT_EQ(object_of(file.get(), "/frames/blocks/position_3"),
            object_of(file.get(), "/frames/blocks/position_0"));
  EXPECT_EQ(object_of(file.get(), "/contacts/blocks/pair_5"),
            object_of(file.get(), "/contacts/blocks/pair_0"));
  EXPECT_FALSE(hdf5::exists(file.get(), "/frames/blocks/position_6"));
}

TEST(FrozenBed, AFrameWithAnotherContactCountIsRefused) {
  FrozenFile dir;
  ResultWriter writer(dir.path, frozen_header(), true);
  FrozenFrame frame(0);
  frame.pair = {0, 1};
  frame.force = {1.0};
  frame.H = {0.01};
  frame.tangential = {0.0, 0.0, 0.0};
  frame.Q = {0.0};
  EXPECT_THROW(writer.write_frame(frame.view(0.0)), std::invalid_argument);
}
