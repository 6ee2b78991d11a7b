// End to end: /contacts/heat_flow. A column of three spheres between a floor at 400 K and a
// ceiling at 300 K, constant contact conductance H: at steady state the same heat flow
// Q = (400 - 300) K / (4 / H) passes through each of the four contacts in series.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The contacts and temperatures of a finished run in `dir` (its scene written as s.toml).
struct HeatFlowRun {
  std::vector<long long> pair, offset;
  std::vector<double> Q, H, T, time;
};

HeatFlowRun run_and_read(const std::string& dir, const std::string& scene) {
  write_file(dir + "/s.toml", scene);
  const auto r = run_tmdem("run s.toml --quiet", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  return {read_ints(f, "/contacts/pair"), read_ints(f, "/frames/contact_offset"),
          read_doubles(f, "/contacts/heat_flow"), read_doubles(f, "/contacts/conductance"),
          read_doubles(f, "/frames/temperature"), read_doubles(f, "/frames/time")};
}

// Three spheres between a floor at 400 K and a ceiling at 300 K, run to steady state (3000 s,
// tolerances 1e-12), a frame every 1000 s in out.h5.
std::string column_between_walls(SceneBuilder scene) {
  return scene.set("simulation.duration", 3000.0)
      .add("generate", column(3))
      .add("wall", floor_wall({{"temperature", 400.0}}))
      .add("wall", plane_wall({0.0, 0.006, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 300.0}}))
      .set(tolerances(1.0e-12))
      .set(output("out.h5", 1000.0))
      .str();
}

}  // namespace

TEST(EndToEndHeatFlow, SeriesColumnCarriesTheSameSteadyHeatFlowThroughEveryContact) {
  const auto run = run_and_read(scratch_dir("heat_flow"), column_between_walls(thermal_scene()));
  const auto& [pair, offset, Q, H, T, time] = run;
  const std::size_t frames = offset.size() - 1;
  ASSERT_EQ(offset[frames] - offset[frames - 1], 4);
  const double H0 = 1.0e-3, expected_W = 100.0 / (4.0 / H0);  // 0.025 W
  for (long long c = offset[frames - 1]; c < offset[frames]; ++c) {
    EXPECT_EQ(H[c], H0);
    const long long i = pair[2 * c], j = pair[2 * c + 1];
    // Positive from i to j: upwards between particles and into the ceiling (wall 1), negative
    // from the floor (wall 0) into particle 0.
    const double sign = j == -1 ? -1.0 : 1.0;
    EXPECT_NEAR(Q[c], sign * expected_W, 1e-6 * expected_W) << i << " " << j;
  }
  // At t = 0 every particle is at 293.15 K: the floor contact carries H (293.15 - 400).
  for (long long c = offset[0]; c < offset[1]; ++c) {
    if (pair[2 * c + 1] == -1) {
      EXPECT_NEAR(Q[c], H0 * (293.15 - 400.0), 1e-15);
    }
  }
}

// The same column with the particle's own resistance (thermal.particle_resistance): each path is
// in series with the shells of its particles, R = (1/(c r) - 1/r) / (k Omega) with Omega the
// cone of the partner (equal touching spheres, and a wall's mirror image: sin theta = 1/2). The
// result file gives each contact's conductance in series, f H, and the flow through it: at
// steady state the same Q = 100 K / (4 / H + 6 R) through all four (two wall paths with one
// shell, two pair paths with two).
TEST(EndToEndHeatFlow, ParticleResistanceIsInTheContactsConductanceAndFlow) {
  const double c = 0.5, r = 1.0e-3, k = 50.0, H0 = 1.0e-3;
  const double omega = 2.0 * std::numbers::pi * (1.0 - std::sqrt(3.0) / 2.0);
  const double R = (1.0 / (c * r) - 1.0 / r) / (k * omega);  // K/W, one shell
  const auto run = run_and_read(
      scratch_dir("heat_flow_shells"),
      column_between_walls(thermal_scene().set(
          {{"thermal.particle_resistance", "isothermal_core"}, {"thermal.core_fraction", c}})));
  const auto& [pair, offset, Q, H, T, time] = run;
  const std::size_t frames = offset.size() - 1;
  ASSERT_EQ(offset[frames] - offset[frames - 1], 4);
  const double expected_W = 100.0 / (4.0 / H0 + 6.0 * R);
  for (long long c_ = offset[frames - 1]; c_ < offset[frames]; ++c_) {
    const long long j = pair[2 * c_ + 1];
    const double shells = j < 0 ? R : 2.0 * R;
    EXPECT_NEAR(H[c_], 1.0 / (1.0 / H0 + shells), 1e-12 * H0) << pair[2 * c_] << " " << j;
    EXPECT_NEAR(Q[c_], (j == -1 ? -1.0 : 1.0) * expected_W, 1e-6 * expected_W) << pair[2 * c_] << " " << j;
  }
}

// A flux floor shares its power by conductance: with equal conductances each of the 9 spheres
// of a 3 x 1 x 3 layer receives P / 9, recorded as a flow from the sphere into the wall of -P/9.
TEST(EndToEndHeatFlow, FluxWallContactsCarryTheirShareOfThePower) {
  const double flux = 2500.0, area = 3.0e-5;  // W/m^2, m^2: P = 75 mW
  const auto run = run_and_read(scratch_dir("heat_flow_flux"),
             thermal_scene()
                 .set("simulation.duration", 20.0)
                 .add("generate", lattice({3, 1, 3}))
                 .add("wall", floor_wall({{"heat_flux", flux}, {"heat_flux_area", area}}))
                 .set(output("out.h5", 10.0))
                 .str());
  const auto& [pair, offset, Q, H, T, time] = run;
  for (std::size_t fr = 0; fr + 1 < offset.size(); ++fr) {
    int floor_contacts = 0;
    for (long long c = offset[fr]; c < offset[fr + 1]; ++c) {
      if (pair[2 * c + 1] != -1) continue;
      ++floor_contacts;
      EXPECT_NEAR(Q[c], -flux * area / 9.0, 1e-15) << fr;
    }
    EXPECT_EQ(floor_contacts, 9) << fr;
  }
}

// A wall whose temperature follows a table: the heat flow uses the table's value at the
// frame's time (300 K at 0 s rising to 400 K at 100 s, then held).
TEST(EndToEndHeatFlow, TabledWallUsesItsTemperatureAtTheFrameTime) {
  const auto run = run_and_read(scratch_dir("heat_flow_table"),
             thermal_scene()
                 .set("simulation.duration", 150.0)
                 .add("generate", column(1))
                 .add("wall", floor_wall({{"temperature", raw("[[0.0, 300.0], [100.0, 400.0]]")}}))
                 .set(tolerances(1.0e-10))
                 .set(output("out.h5", 50.0))
                 .str());
  const auto& [pair, offset, Q, H, T, time] = run;
  ASSERT_EQ(time.size(), 4u);
  for (std::size_t fr = 0; fr < time.size(); ++fr) {
    ASSERT_EQ(offset[fr + 1] - offset[fr], 1) << fr;
    const double wall_K = 300.0 + std::min(time[fr], 100.0);
    const auto c = std::size_t(offset[fr]);
    EXPECT_EQ(H[c], 1.0e-3);
    EXPECT_NEAR(Q[c], H[c] * (T[fr] - wall_K), 1e-15) << time[fr];
  }
}
