// RESULT.xdmf opened by ParaView itself (pvbatch, Debian's paraview + python3-paraview, installed
// by scripts/setup.sh --with-paraview): Xdmf3 Reader S, Xdmf3 Reader T and the legacy XDMF
// Reader all show the particles (point count, time steps, a temperature of the last frame taken
// from the HDF5 file), the contact line set and the walls. Skipped when pvbatch is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "e2e/E2eSupport.h"

using namespace tmdem::e2e;

namespace {

bool have_pvbatch() { return std::system("command -v pvbatch > /dev/null 2>&1") == 0; }

// What the readers must show at one frame of a result, read from the HDF5 file.
struct Expected {
  std::size_t particles = 0, frames = 0, probe = 0, walls = 0;
  double last_time_s = 0.0, at_s = 0.0, temperature_K = 0.0;
  long long contacts = 0;
  double wall_y_m = std::numeric_limits<double>::quiet_NaN();  // a square at this y (NaN: no check)
  double longest_line_m = std::numeric_limits<double>::quiet_NaN();  // no contact line longer (NaN: no check)
};

Expected expected_at(const std::string& h5, std::size_t frame, std::size_t probe,
                     std::size_t walls) {
  H5::H5File f(h5, H5F_ACC_RDONLY);
  const auto time = read_doubles(f, "/frames/time");
  std::vector<hsize_t> dims;
  const auto T = read_doubles(f, "/frames/temperature", &dims);
  const auto offset = read_ints(f, "/frames/contact_offset");
  Expected e;
  e.particles = dims[1];
  e.frames = time.size();
  e.last_time_s = time.back();
  e.at_s = time[frame];
  e.probe = probe;
  e.temperature_K = T[frame * e.particles + probe];
  e.contacts = offset[frame + 1] - offset[frame];
  e.walls = walls;
  return e;
}

// Runs check_xdmf.py through pvbatch; its output, and whether every reader passed.
bool readers_show(const std::string& xdmf, const Expected& e, std::string& log) {
  char numbers[256];
  std::snprintf(numbers, sizeof numbers, "%zu %zu %.17g %zu %.17g %lld %zu %.17g", e.particles,
                e.frames, e.last_time_s, e.probe, e.temperature_K, e.contacts, e.walls, e.at_s);
  std::string arguments = numbers;
  if (!std::isnan(e.wall_y_m) || !std::isnan(e.longest_line_m)) {
    std::snprintf(numbers, sizeof numbers, " %.17g", e.wall_y_m);
    arguments += std::isnan(e.wall_y_m) ? " nan" : numbers;
  }
  if (!std::isnan(e.longest_line_m)) {
    std::snprintf(numbers, sizeof numbers, " %.17g", e.longest_line_m);
    arguments += numbers;
  }
  const std::string out = xdmf + ".pvbatch.log";
  const std::string command = "pvbatch '" + std::string(TMDEM_SOURCE_DIR) +
                              "/tests/paraview/check_xdmf.py' '" + xdmf + "' " + arguments +
                              " > '" + out + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  log = text.str();
  return status == 0;
}

// Steel in 3D under gravity with the given mechanics, for `duration_s`, on a floor at 373.15 K.
SceneBuilder heated_from_below(double duration_s, const char* mechanics) {
  return steel_scene()
      .set({{"simulation.duration", duration_s},
            {"simulation.dimension", 3},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", mechanics}})
      .add("wall", floor_wall({{"temperature", 373.15}}));
}

// Writes DIR/STEM.toml and runs it (tmdem run STEM.toml --quiet in DIR).
ProgramResult run_scene(const std::string& dir, const std::string& stem, const std::string& scene) {
  write_file(dir + "/" + stem + ".toml", scene);
  return run_tmdem("run " + stem + ".toml --quiet", dir);
}

// Every test needs ParaView's pvbatch; skipped without it.
class ParaView : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_pvbatch()) GTEST_SKIP() << "pvbatch not found (scripts/setup.sh --with-paraview)";
  }
};

}  // namespace

TEST_F(ParaView, AllThreeXdmfReadersShowParticlesContactsAndWalls) {
  const auto dir = scratch_dir("paraview");
  // 18 steel spheres settled on a hot floor between two side walls, heated for 60 s.
  const auto r = run_scene(dir, "bed",
                           heated_from_below(60.0, "settle")
                               .add("generate", lattice({3, 2, 3}))
                               .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
                               .add("wall", plane_wall({0.006, 0.0, 0.0}, {-1.0, 0.0, 0.0}))
                               .set(output("bed.h5", 20.0)));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const std::string xdmf = std::filesystem::absolute(dir + "/bed.xdmf").string();
  const Expected last = expected_at(dir + "/bed.h5", 3, 1, 3);  // particle 1: bottom layer
  ASSERT_EQ(last.frames, 4u);
  ASSERT_GT(last.temperature_K, 293.15 + 1.0);  // it did heat up: not an initial value
  ASSERT_GT(last.contacts, 0);
  std::string log;
  EXPECT_TRUE(readers_show(xdmf, last, log)) << log;
  for (const char* reader : {"Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader"})
    EXPECT_NE(log.find(std::string(reader) + ": 4 time steps"), std::string::npos) << log;
}

TEST_F(ParaView, DynamicPourShowsMovingParticlesAndAFirstFrameWithoutContacts) {
  const auto dir = scratch_dir("paraview_pour");
  // Four spheres 1 mm above a hot floor, 3 mm apart: no contact at t = 0, on the floor later.
  const auto r = run_scene(dir, "pour",
                           heated_from_below(0.2, "dynamic")
                               .add("generate", lattice({2, 1, 2}, {{"spacing", 0.003},
                                                                    {"origin", {0.0015, 0.002, 0.0015}}}))
                               .set(output("pour.h5", 0.1)));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string xdmf = std::filesystem::absolute(dir + "/pour.xdmf").string();
  const Expected first = expected_at(dir + "/pour.h5", 0, 2, 1);
  const Expected last = expected_at(dir + "/pour.h5", 2, 2, 1);
  ASSERT_EQ(first.frames, 3u);
  ASSERT_EQ(first.contacts, 0);
  ASSERT_EQ(last.contacts, 4);  // each sphere on the floor
  ASSERT_GT(last.temperature_K, 293.15);
  std::string log;
  EXPECT_TRUE(readers_show(xdmf, first, log)) << log;
  EXPECT_TRUE(readers_show(xdmf, last, log)) << log;
}

// A piston falls 1 mm onto a 2 x 2 x 2 lattice: the readers draw it where /frames/wall_position
// has it in each frame, not where it started (ParaView drew every wall at its first place before
// the frames had their own wall corners).
TEST_F(ParaView, PistonIsDrawnWhereItIsInEachFrame) {
  const auto dir = scratch_dir("paraview_piston");
  const auto r = run_scene(dir, "piston",
                           heated_from_below(0.04, "dynamic")
                               .add("generate", lattice({2, 2, 2}))
                               .add("wall", plane_wall({0.0, 0.005, 0.0}, {0.0, -1.0, 0.0},
                                                       {{"piston", true}, {"mass", 1e-3}, {"force", 0.1}}))
                               .set(output("piston.h5", 0.02)));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File f(dir + "/piston.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto wall_at = read_doubles(f, "/frames/wall_position", &dims);  // [F, 2, 3]
  ASSERT_EQ(dims.size(), 3u);
  ASSERT_EQ(dims[0], 3u);
  const std::string xdmf = std::filesystem::absolute(dir + "/piston.xdmf").string();
  for (std::size_t frame : {0u, 2u}) {
    Expected e = expected_at(dir + "/piston.h5", frame, 0, 2);
    e.wall_y_m = wall_at[(frame * 2 + 1) * 3 + 1];
    if (frame == 2) { ASSERT_LT(e.wall_y_m, 0.0045) << "the piston did not fall"; }
    std::string log;
    EXPECT_TRUE(readers_show(xdmf, e, log)) << "frame " << frame << ": " << log;
  }
}

// A lattice periodic along x and z (6 mm periods, no side walls) on a hot floor, contacts from
// geometry: the pairs round the boundaries end at the neighbour's image beside the sphere
// (/xdmf/frame_<f>/image_ends), so every reader shows each contact as one line no longer than a
// diameter; drawn between the wrapped centres they would be 4 mm long.
TEST_F(ParaView, ContactsRoundAPeriodicBoundaryAreShortLines) {
  const auto dir = scratch_dir("paraview_periodic");
  const auto r = run_scene(dir, "periodic",
                           heated_from_below(20.0, "off")
                               .set({{"thermal.conductance", "constant"}})
                               .set({{"periodic.x", {0.0, 0.006}}, {"periodic.z", {0.0, 0.006}}})
                               .add("generate", lattice({3, 2, 3}))
                               .set(output("periodic.h5", 10.0)));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  {
    H5::H5File f(dir + "/periodic.h5", H5F_ACC_RDONLY);
    std::vector<hsize_t> dims;
    read_doubles(f, "/xdmf/frame_2/image_ends", &dims);
    ASSERT_EQ(dims[0], 12u);  // one per pair round a boundary: 2 layers x 2 axes x 3 rows
  }
  const std::string xdmf = std::filesystem::absolute(dir + "/periodic.xdmf").string();
  Expected e = expected_at(dir + "/periodic.h5", 2, 1, 1);
  ASSERT_GT(e.contacts, 0);
  e.longest_line_m = 0.002 * (1.0 + 1e-6);
  std::string log;
  EXPECT_TRUE(readers_show(xdmf, e, log)) << log;
  // The check can fail: every contact line is 2 mm long.
  e.longest_line_m = 0.0019;
  EXPECT_FALSE(readers_show(xdmf, e, log)) << log;
}
