// RESULT.xdmf opened by ParaView itself (pvbatch, Debian's paraview + python3-paraview, installed
// by scripts/setup.sh --with-paraview): Xdmf3 Reader S, Xdmf3 Reader T and the legacy XDMF
// Reader all show the particles (point count, time steps, a temperature of the last frame taken
// from the HDF5 file), the contact line set and the walls. Skipped when pvbatch is absent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "e2e/E2eSupport.h"

using namespace tmdem::e2e;

namespace {

bool have_pvbatch() { return std::system("command -v pvbatch > /dev/null 2>&1") == 0; }

// What the readers must show at one frame of a result, read from the HDF5 file.
struct Expected {
  std::size_t particles = 0, frames = 0, probe = 0, walls = 0;
  double last_time_s = 0.0, at_s = 0.0, temperature_K = 0.0;
  long long contacts = 0;
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
  const std::string out = xdmf + ".pvbatch.log";
  const std::string command = "pvbatch '" + std::string(TMDEM_SOURCE_DIR) +
                              "/tests/paraview/check_xdmf.py' '" + xdmf + "' " + numbers +
                              " > '" + out + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  log = text.str();
  return status == 0;
}

}  // namespace

TEST(ParaView, AllThreeXdmfReadersShowParticlesContactsAndWalls) {
  if (!have_pvbatch()) GTEST_SKIP() << "pvbatch not found (scripts/setup.sh --with-paraview)";
  const auto dir = scratch_dir("paraview");
  // 18 steel spheres settled on a hot floor between two side walls, heated for 60 s.
  write_file(dir + "/bed.toml",
             steel_scene()
                 .set({{"simulation.duration", 60.0},
                       {"simulation.dimension", 3},
                       {"simulation.gravity", {0.0, -9.81, 0.0}},
                       {"effects.mechanics", "settle"}})
                 .add("generate", lattice({3, 2, 3}))
                 .add("wall", floor_wall({{"temperature", 373.15}}))
                 .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
                 .add("wall", plane_wall({0.006, 0.0, 0.0}, {-1.0, 0.0, 0.0}))
                 .set(output("bed.h5", 20.0)));
  const auto r = run_tmdem("run bed.toml --quiet", dir);
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

TEST(ParaView, DynamicPourShowsMovingParticlesAndAFirstFrameWithoutContacts) {
  if (!have_pvbatch()) GTEST_SKIP() << "pvbatch not found (scripts/setup.sh --with-paraview)";
  const auto dir = scratch_dir("paraview_pour");
  // Four spheres 1 mm above a hot floor, 3 mm apart: no contact at t = 0, on the floor later.
  write_file(dir + "/pour.toml",
             steel_scene()
                 .set({{"simulation.duration", 0.2},
                       {"simulation.dimension", 3},
                       {"simulation.gravity", {0.0, -9.81, 0.0}},
                       {"effects.mechanics", "dynamic"}})
                 .add("generate", lattice({2, 1, 2}, {{"spacing", 0.003},
                                                      {"origin", {0.0015, 0.002, 0.0015}}}))
                 .add("wall", floor_wall({{"temperature", 373.15}}))
                 .set(output("pour.h5", 0.1)));
  const auto r = run_tmdem("run pour.toml --quiet", dir);
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
