// ResultViews: the per-frame datasets RESULT.xdmf names read back exactly the frame's rows of
// /frames and /contacts (virtual datasets), the contact line set ends wall contacts at the foot
// of the centre on the wall, and a restart cuts the views back with the frames.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "coupling/output/Hdf5Io.h"
#include "coupling/output/ResultWriter.h"
#include "coupling/output/XdmfWriter.h"
#include "ScratchResultFile.h"
#include "ThreeParticleHeader.h"

namespace {

namespace fs = std::filesystem;
using namespace tmdem::coupling;

struct ViewFile : test::ScratchResultFile {
  ViewFile() : ScratchResultFile("views") {}
};

ResultHeader three_particles() {
  ResultHeader header = test::three_particle_header();
  WallPlane floor;  // y = 0, facing up, 350 K
  floor.normal = {0.0, 1.0, 0.0};
  floor.temperature_K = 350.0;
  WallPlane side;   // x = -1 mm, facing +x, adiabatic
  side.point_m = {-1e-3, 0.0, 0.0};
  side.normal = {1.0, 0.0, 0.0};
  header.walls = {floor, side};
  return header;
}

// Frame f: positions shifted by f mm in z, temperatures 300 + 10 f + i; contacts (0, 1) and
// (0, floor) in frame 0, (1, 2), (2, side) and (0, floor) in frame 1.
struct ViewFrame {
  std::vector<double> x, v, T, force, H, tangential, Q;
  std::vector<std::int64_t> pair;
  FrameView view(double t) const {
    return FrameView{t, x, v, T, 1.0, 0.0, pair, force, H, tangential, Q, {}};
  }
};

ViewFrame frame(int f) {
  ViewFrame fr;
  fr.x = {0.0, 1e-3, 1e-3 * f, 2e-3, 1e-3, 1e-3 * f, 5e-3, 2e-3, 1e-3 * f};
  fr.v = {0.0, 0.0, 0.1 * f, 0.0, 0.0, 0.2 * f, 0.0, 0.0, 0.3 * f};
  fr.T = {300.0 + 10 * f, 301.0 + 10 * f, 302.0 + 10 * f};
  if (f == 0) {
    fr.pair = {0, 1, 0, -1};
  } else {
    fr.pair = {1, 2, 2, -2, 0, -1};
  }
  const std::size_t c = fr.pair.size() / 2;
  for (std::size_t k = 0; k < c; ++k) {
    fr.force.push_back(1.0 + double(k) + 10.0 * f);
    fr.H.push_back(0.01 * double(k + 1));
    fr.Q.push_back(-0.5 * double(k + 1) - f);
    for (int d = 0; d < 3; ++d) fr.tangential.push_back(0.1 * d + double(k));
  }
  return fr;
}

std::vector<double> read_view(const std::string& path, const std::string& name) {
  Hdf5Handle file = hdf5::open_file(path, false, false);
  Hdf5Handle d = hdf5::open_dataset(file.get(), name.c_str());
  const auto dims = hdf5::dataset_dims(d.get());
  hsize_t n = 1;
  for (hsize_t x : dims) n *= x;
  std::vector<double> out(n);
  hdf5::read_rows(d.get(), 0, dims[0], out.data(), H5T_NATIVE_DOUBLE);
  return out;
}

std::vector<std::int64_t> read_ids(const std::string& path, const std::string& name) {
  Hdf5Handle file = hdf5::open_file(path, false, false);
  Hdf5Handle d = hdf5::open_dataset(file.get(), name.c_str());
  const auto dims = hdf5::dataset_dims(d.get());
  std::vector<std::int64_t> out(dims[0] * (dims.size() > 1 ? dims[1] : 1));
  hdf5::read_rows(d.get(), 0, dims[0], out.data(), H5T_NATIVE_INT64);
  return out;
}

bool has(const std::string& path, const std::string& name) {
  Hdf5Handle file = hdf5::open_file(path, false, false);
  return H5Lexists(file.get(), "/xdmf", H5P_DEFAULT) > 0 &&
         H5Lexists(file.get(), name.c_str(), H5P_DEFAULT) > 0;
}

TEST(ResultViews, FrameViewsReadTheFrameRowsExactly) {
  ViewFile file;
  {
    ResultWriter writer(file.path, three_particles(), true);
    for (int f = 0; f < 2; ++f) writer.write_frame(frame(f).view(0.5 * f));
    writer.finish("ok");
  }
  for (int f = 0; f < 2; ++f) {
    const ViewFrame expected = frame(f);
    const std::string view = "/xdmf/frame_" + std::to_string(f) + "/";
    EXPECT_EQ(read_view(file.path, view + "position"), expected.x) << f;
    EXPECT_EQ(read_view(file.path, view + "velocity"), expected.v) << f;
    EXPECT_EQ(read_view(file.path, view + "temperature"), expected.T) << f;
    EXPECT_EQ(read_view(file.path, view + "normal_force"), expected.force) << f;
    EXPECT_EQ(read_view(file.path, view + "conductance"), expected.H) << f;
    EXPECT_EQ(read_view(file.path, view + "heat_flow"), expected.Q) << f;
    EXPECT_EQ(read_view(file.path, view + "tangential_force"), expected.tangential) << f;
  }
  // Frame 1: (1, 2), (2, side wall) -> point N + 0, (0, floor) -> point N + 1.
  EXPECT_EQ(read_ids(file.path, "/xdmf/frame_1/contact_lines"),
            (std::vector<std::int64_t>{1, 2, 2, 3, 0, 4}));
  // Feet: particle 2 (5, 2, 1) mm on x = -1 mm; particle 0 (0, 1, 1) mm on y = 0.
  const std::vector<double> feet = {-1e-3, 2e-3, 1e-3, 0.0, 0.0, 1e-3};
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_1/wall_feet"), feet);
  std::vector<double> points = frame(1).x;
  points.insert(points.end(), feet.begin(), feet.end());
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_1/contact_points"), points);
  EXPECT_EQ(read_ids(file.path, "/xdmf/vertices"), (std::vector<std::int64_t>{0, 1, 2}));
  // Walls as given; adiabatic is NaN. Each square lies in its plane.
  const auto T_wall = read_view(file.path, "/walls/temperature");
  ASSERT_EQ(T_wall.size(), 2u);
  EXPECT_EQ(T_wall[0], 350.0);
  EXPECT_TRUE(std::isnan(T_wall[1]));
  const auto corners = read_view(file.path, "/xdmf/walls/points");
  ASSERT_EQ(corners.size(), 24u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(corners[3 * k + 1], 0.0, 1e-18);             // floor: y = 0
    EXPECT_NEAR(corners[12 + 3 * k], -1e-3, 1e-18);          // side: x = -1 mm
  }
}

TEST(ResultViews, CylinderWallContactsEndOnTheMantleAndItIsDrawnAsStrips) {
  ViewFile file;
  ResultHeader header = three_particles();
  WallPlane tube;  // axis along y through (2, 0, 0) mm, radius 4 mm, 320 K
  tube.point_m = {2e-3, 0.0, 0.0};
  tube.normal = {0.0, 1.0, 0.0};
  tube.radius_m = 4e-3;
  tube.temperature_K = 320.0;
  header.walls = {tube};
  ViewFrame f = frame(0);
  f.pair = {2, -1};  // particle 2 at (5, 2, 0) mm: 3 mm out along +x, foot at (6, 2, 0) mm
  f.force = {1.0};
  f.H = {0.01};
  f.Q = {-0.5};
  f.tangential = {0.0, 0.0, 0.0};
  {
    ResultWriter writer(file.path, header, true);
    writer.write_frame(f.view(0.0));
    writer.finish("ok");
  }
  const auto feet = read_view(file.path, "/xdmf/frame_0/wall_feet");
  ASSERT_EQ(feet.size(), 3u);
  EXPECT_NEAR(feet[0], 6e-3, 1e-18);
  EXPECT_NEAR(feet[1], 2e-3, 1e-18);
  EXPECT_NEAR(feet[2], 0.0, 1e-18);
  EXPECT_EQ(read_view(file.path, "/walls/radius"), (std::vector<double>{4e-3}));
  const auto corners = read_view(file.path, "/xdmf/walls/points");
  ASSERT_EQ(corners.size(), 32u * 4u * 3u);
  for (std::size_t k = 0; k < corners.size() / 3; ++k) {  // every corner on the mantle
    const double dx = corners[3 * k] - 2e-3, dz = corners[3 * k + 2];
    EXPECT_NEAR(std::hypot(dx, dz), 4e-3, 1e-15) << k;
  }
  EXPECT_EQ(read_view(file.path, "/xdmf/walls/temperature"), std::vector<double>(32, 320.0));
}

TEST(ResultViews, RestartCutsTheViewsBackWithTheFrames) {
  ViewFile file;
  {
    ResultWriter writer(file.path, three_particles(), true);
    for (int f = 0; f < 2; ++f) writer.write_frame(frame(f).view(0.5 * f));
    writer.finish("interrupted");
  }
  {
    ResultWriter writer = ResultWriter::reopen(file.path, 1);
    EXPECT_FALSE(has(file.path, "/xdmf/frame_1"));
    // Frame 1 again, with other data: its view shows the new rows.
    ViewFrame again = frame(1);
    again.T = {400.0, 401.0, 402.0};
    writer.write_frame(again.view(0.5));
    writer.finish("ok");
  }
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_1/temperature"),
            (std::vector<double>{400.0, 401.0, 402.0}));
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_1/normal_force"), frame(1).force);
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_0/normal_force"), frame(0).force);
}

// A piston moves: the frames where a wall stands away from /walls/point get their own wall
// corners, the drawn ones shifted by the wall's displacement, and RESULT.xdmf names them (before,
// ParaView drew every wall where it started). A reopened file keeps counting them.
TEST(ResultViews, MovedWallsGetTheirOwnCornersPerFrame) {
  ViewFile file;
  // wall_position per frame: frame 0 as drawn, frame 1 the floor 0.5 mm up, frame 2 it and the
  // side wall 0.25 mm along -x.
  const std::vector<std::vector<double>> walls_at = {{0.0, 0.0, 0.0, -1e-3, 0.0, 0.0},
                                                     {0.0, 5e-4, 0.0, -1e-3, 0.0, 0.0},
                                                     {0.0, 5e-4, 0.0, -1.25e-3, 0.0, 0.0}};
  {
    ResultWriter writer(file.path, three_particles(), true);
    for (int f = 0; f < 2; ++f) {
      ViewFrame fr = frame(f);
      FrameView view = fr.view(0.5 * f);
      view.wall_point_m = walls_at[f];
      writer.write_frame(view);
    }
    writer.finish("interrupted");
  }
  {
    ResultWriter writer = ResultWriter::reopen(file.path, 2);
    ViewFrame fr = frame(1);
    FrameView view = fr.view(1.0);
    view.wall_point_m = walls_at[2];
    writer.write_frame(view);
    writer.finish("ok");
  }
  EXPECT_FALSE(has(file.path, "/xdmf/frame_0/wall_points"));
  const auto drawn = read_view(file.path, "/xdmf/walls/points");
  ASSERT_EQ(drawn.size(), 24u);  // two planes, one quad each
  for (int f = 1; f < 3; ++f) {
    const auto moved = read_view(file.path, "/xdmf/frame_" + std::to_string(f) + "/wall_points");
    ASSERT_EQ(moved.size(), 24u) << f;
    for (int c = 0; c < 8; ++c) {
      const int w = c / 4;  // corners 0-3: the floor, 4-7: the side wall
      for (int k = 0; k < 3; ++k)
        EXPECT_DOUBLE_EQ(moved[3 * c + k],
                         drawn[3 * c + k] + walls_at[f][3 * w + k] - walls_at[0][3 * w + k])
            << "frame " << f << " corner " << c << " axis " << k;
    }
  }
  // The floor's corners lie on y = 0.5 mm in frames 1 and 2.
  const auto moved = read_view(file.path, "/xdmf/frame_1/wall_points");
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(moved[3 * c + 1], 5e-4, 1e-18);
  // RESULT.xdmf: frame 0 names the drawn corners, frames 1 and 2 their own.
  std::ifstream in(xdmf_path_for(file.path));
  const std::string xdmf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto walls_block = xdmf.substr(xdmf.find("<Grid Name=\"walls\""));
  EXPECT_NE(walls_block.find(":/xdmf/walls/points<"), std::string::npos);
  EXPECT_NE(walls_block.find(":/xdmf/frame_1/wall_points<"), std::string::npos);
  EXPECT_NE(walls_block.find(":/xdmf/frame_2/wall_points<"), std::string::npos);
  EXPECT_EQ(walls_block.find(":/xdmf/frame_0/wall_points<"), std::string::npos);
}

// The HDF5 object a path names (hard links to one object give the same address).
haddr_t object_of(const std::string& path, const std::string& name) {
  Hdf5Handle file = hdf5::open_file(path, false, false);
  H5O_info_t info;
  EXPECT_GE(H5Oget_info_by_name(file.get(), name.c_str(), &info, H5P_DEFAULT), 0) << name;
  return info.addr;
}

bool same_object(const std::string& path, const std::string& a, const std::string& b) {
  return object_of(path, a) == object_of(path, b);
}

TEST(ResultViews, FrozenFramesLinkTheirGeometryAndContactViewsToTheFirst) {
  ViewFile file;
  ViewFrame frozen = frame(1);
  {
    ResultWriter writer(file.path, three_particles(), true);
    for (int f = 0; f < 3; ++f) {
      ViewFrame now = frozen;  // same geometry and contacts, other temperatures and heat flows
      for (double& T : now.T) T += f;
      for (double& Q : now.Q) Q *= f + 1;
      writer.write_frame(now.view(0.5 * f));
    }
    ViewFrame moved = frozen;  // frame 3: a particle moved
    moved.x[0] += 1e-6;
    writer.write_frame(moved.view(1.5));
    writer.finish("ok");
  }
  for (const char* name : {"position", "velocity", "contact_lines", "wall_feet", "contact_points",
                           "normal_force", "conductance", "tangential_force"}) {
    EXPECT_TRUE(same_object(file.path, "/xdmf/frame_0/" + std::string(name),
                            "/xdmf/frame_2/" + std::string(name)))
        << name;
    EXPECT_FALSE(same_object(file.path, "/xdmf/frame_0/" + std::string(name),
                             "/xdmf/frame_3/" + std::string(name)))
        << name;
  }
  for (int f = 0; f < 3; ++f) {
    const std::string view = "/xdmf/frame_" + std::to_string(f) + "/";
    EXPECT_FALSE(same_object(file.path, "/xdmf/frame_0/temperature", view + "temperature") &&
                 f > 0);
    std::vector<double> T = frozen.T, Q = frozen.Q;
    for (double& t : T) t += f;
    for (double& q : Q) q *= f + 1;
    EXPECT_EQ(read_view(file.path, view + "temperature"), T) << f;
    EXPECT_EQ(read_view(file.path, view + "heat_flow"), Q) << f;
    EXPECT_EQ(read_view(file.path, view + "position"), frozen.x) << f;
  }
  std::vector<double> moved = frozen.x;
  moved[0] += 1e-6;
  EXPECT_EQ(read_view(file.path, "/xdmf/frame_3/position"), moved);
}

TEST(ResultViews, GrowingDatasetsAreCompressed) {
  ViewFile file;
  {
    ResultWriter writer(file.path, three_particles(), true);
    writer.write_frame(frame(0).view(0.0));
    writer.finish("ok");
  }
  Hdf5Handle h5 = hdf5::open_file(file.path, false, false);
  for (const char* name : {"/frames/position", "/frames/temperature", "/contacts/pair",
                           "/contacts/heat_flow"}) {
    Hdf5Handle d = hdf5::open_dataset(h5.get(), name);
    Hdf5Handle plist(H5Dget_create_plist(d.get()), H5Pclose);
    bool deflate = false;
    for (int k = 0; k < H5Pget_nfilters(plist.get()); ++k) {
      unsigned flags = 0;
      std::size_t count = 0;
      deflate = deflate || H5Pget_filter2(plist.get(), unsigned(k), &flags, &count, nullptr, 0,
                                          nullptr, nullptr) == H5Z_FILTER_DEFLATE;
    }
    EXPECT_TRUE(deflate) << name;
  }
}

}  // namespace

// Periodic along x with period 6.5 mm from -1 mm: particles 0 (x = 0) and 2 (x = 5 mm) touch
// round the boundary, 1.5 mm apart. Their line ends at the image of 2 beside 0, x = -1.5 mm,
// rather than spanning the box; /periodic describes the box.
TEST(ResultViews, ContactsRoundAPeriodicBoundaryEndAtTheImageBesideI) {
  ViewFile file;
  ResultHeader header = three_particles();
  header.periodic.axis = {true, false, false};
  header.periodic.low_m = {-1e-3, 0.0, 0.0};
  header.periodic.high_m = {5.5e-3, 0.0, 0.0};
  ViewFrame fr = frame(0);
  fr.pair = {0, 2, 0, -1, 0, 1};
  fr.force = {1.0, 2.0, 3.0};
  fr.H = {0.1, 0.2, 0.3};
  fr.Q = {-1.0, -2.0, -3.0};
  fr.tangential.assign(9, 0.0);
  {
    ResultWriter writer(file.path, header, true);
    writer.write_frame(fr.view(0.0));
    writer.write_frame(fr.view(1.0));  // the same contacts: views linked to frame 0's
    writer.finish("ok");
  }
  EXPECT_EQ(read_ids(file.path, "/periodic/axis"), (std::vector<std::int64_t>{1, 0, 0}));
  EXPECT_EQ(read_view(file.path, "/periodic/low"), (std::vector<double>{-1e-3, 0.0, 0.0}));
  EXPECT_EQ(read_view(file.path, "/periodic/high"), (std::vector<double>{5.5e-3, 0.0, 0.0}));
  for (const std::string view : {"/xdmf/frame_0/", "/xdmf/frame_1/"}) {
    // (0, 2) -> the image, point N + W = 4; (0, floor) -> foot N + 0 = 3; (0, 1) as it is.
    EXPECT_EQ(read_ids(file.path, view + "contact_lines"), (std::vector<std::int64_t>{0, 4, 0, 3, 0, 1}));
    const auto image = read_view(file.path, view + "image_ends");
    ASSERT_EQ(image.size(), 3u);
    EXPECT_NEAR(image[0], -1.5e-3, 1e-18);
    EXPECT_EQ(image[1], 2e-3);
    EXPECT_EQ(image[2], 0.0);
    EXPECT_EQ(read_view(file.path, view + "contact_points").size(), 3u * 5u);
  }
  // The XDMF gives the line set its 5 points (3 particles, a foot, an image).
  std::ifstream xdmf(fs::path(file.path).replace_extension(".xdmf"));
  const std::string text{std::istreambuf_iterator<char>(xdmf), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("Dimensions=\"5 3\""), std::string::npos) << text;
  // Without [periodic] the file has no /periodic and the same pair spans the box.
  ViewFile open_file;
  {
    ResultWriter writer(open_file.path, three_particles(), true);
    writer.write_frame(fr.view(0.0));
    writer.finish("ok");
  }
  EXPECT_FALSE(has(open_file.path, "/periodic"));
  EXPECT_EQ(read_ids(open_file.path, "/xdmf/frame_0/contact_lines"), (std::vector<std::int64_t>{0, 2, 0, 3, 0, 1}));
}
