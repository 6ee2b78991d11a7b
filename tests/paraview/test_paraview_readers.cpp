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

  H5::H5File f(dir + "/bed.h5", H5F_ACC_RDONLY);
  const auto time = read_doubles(f, "/frames/time");
  std::vector<hsize_t> dims;
  const auto T = read_doubles(f, "/frames/temperature", &dims);
  const auto offset = read_ints(f, "/frames/contact_offset");
  const std::size_t frames = time.size(), n = dims[1];
  ASSERT_EQ(frames, 4u);
  const std::size_t probe = 1;  // bottom layer, next to the hot floor
  const double T_last = T[(frames - 1) * n + probe];
  ASSERT_GT(T_last, 293.15 + 1.0);  // it did heat up: the check is not of an initial value
  const long long contacts = offset[frames] - offset[frames - 1];
  ASSERT_GT(contacts, 0);

  const std::string xdmf = std::filesystem::absolute(dir + "/bed.xdmf").string();
  char expected_T[64];
  std::snprintf(expected_T, sizeof expected_T, "%.17g", T_last);
  const std::string command =
      "pvbatch '" + std::string(TMDEM_SOURCE_DIR) + "/tests/paraview/check_xdmf.py' '" + xdmf +
      "' " + std::to_string(n) + " " + std::to_string(frames) + " " + std::to_string(time.back()) +
      " " + std::to_string(probe) + " " + expected_T + " " + std::to_string(contacts) + " 3 > '" +
      dir + "/pvbatch.log' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream log(dir + "/pvbatch.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(status, 0) << text.str();
  for (const char* reader : {"Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader"})
    EXPECT_NE(text.str().find(std::string(reader) + ": 4 time steps"), std::string::npos)
        << text.str();
}
