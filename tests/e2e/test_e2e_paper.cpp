// The reference paper's two cases, settled and heated end to end through the program.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

void check_heated_packing(const std::string& dir, const std::string& file, std::size_t n,
                          double max_penetration_m) {
  H5::H5File f(dir + "/" + file, H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(f, "status"), "ok");
  std::vector<hsize_t> dims;
  const auto T = read_doubles(f, "/frames/temperature", &dims);
  ASSERT_EQ(dims[1], n);
  const std::size_t frames = dims[0];
  ASSERT_GE(frames, 2u);
  // Maximum principle and exact conservation (adiabatic walls, no other mode).
  for (double x : T) {
    ASSERT_GE(x, 293.15 - 1e-6);
    ASSERT_LE(x, 373.15 + 1e-6);
  }
  const auto E = read_doubles(f, "/frames/thermal_energy");
  for (double e : E) EXPECT_NEAR(e, E[0], 1e-10 * E[0]);
  // Heat has left the hot particles: the hottest is cooler, and some cold particle warmer.
  double hottest_end = 0.0, coldest_gain = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    hottest_end = std::max(hottest_end, T[(frames - 1) * n + i]);
    if (T[i] < 300.0) coldest_gain = std::max(coldest_gain, T[(frames - 1) * n + i] - T[i]);
  }
  EXPECT_LT(hottest_end, 373.15 - 1.0);
  EXPECT_GT(coldest_gain, 1.0);
  // Contacts carry compressive forces and Hertz conductances.
  const auto force = read_doubles(f, "/contacts/normal_force");
  const auto H = read_doubles(f, "/contacts/conductance");
  const auto pair = read_ints(f, "/contacts/pair");
  ASSERT_FALSE(force.empty());
  for (std::size_t c = 0; c < force.size(); ++c) {
    EXPECT_GT(force[c], 0.0);
    if (pair[2 * c + 1] >= 0) {
      EXPECT_GT(H[c], 0.0);
    } else {
      EXPECT_EQ(H[c], 0.0);  // the walls are adiabatic
    }
  }
  const auto s = read_summary(dir + "/s.json");
  EXPECT_LT(s["mechanics"]["max_penetration_m"].get<double>(), max_penetration_m);
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-10);
}

}  // namespace

TEST(EndToEndPaper, TriangleOf14DisksSettlesAndHeats) {
  const auto dir = scratch_dir("paper_triangle");
  const auto r = run_tmdem(std::string("run ") + TMDEM_SOURCE_DIR +
                               "/examples/paper_triangle.toml --quiet --summary s.json",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  check_heated_packing(dir, "paper_triangle.h5", 14, 1e-9);
}

TEST(EndToEndPaper, DefaultSceneIsThe256ParticleBedSettledAndHeated) {
  const auto dir = scratch_dir("paper_bed");
  const auto r = run_tmdem("run --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // 1e-5 settling tolerance leaves micrometre overlaps on 0.5-1 mm particles (measured 1.2e-6 m).
  check_heated_packing(dir, "tmdem-default.h5", 256, 5e-6);
}
