// End to end: /contacts/heat_flow. A column of three spheres between a floor at 400 K and a
// ceiling at 300 K, constant contact conductance H: at steady state the same heat flow
// Q = (400 - 300) K / (4 / H) passes through each of the four contacts in series.
#include <gtest/gtest.h>

#include <cmath>

#include "E2eSupport.h"

using namespace tmdem::e2e;

TEST(EndToEndHeatFlow, SeriesColumnCarriesTheSameSteadyHeatFlowThroughEveryContact) {
  const auto dir = scratch_dir("heat_flow");
  write_file(dir + "/s.toml",
             thermal_scene()
                 .set("simulation.duration", 3000.0)
                 .add("generate", column(3))
                 .add("wall", floor_wall({{"temperature", 400.0}}))
                 .add("wall", plane_wall({0.0, 0.006, 0.0}, {0.0, -1.0, 0.0},
                                         {{"temperature", 300.0}}))
                 .set(tolerances(1.0e-12))
                 .set(output("out.h5", 1000.0)));
  const auto r = run_tmdem("run s.toml --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  const auto pair = read_ints(f, "/contacts/pair");
  const auto Q = read_doubles(f, "/contacts/heat_flow");
  const auto H = read_doubles(f, "/contacts/conductance");
  const auto offset = read_ints(f, "/frames/contact_offset");
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
  for (long long c = offset[0]; c < offset[1]; ++c)
    if (pair[2 * c + 1] == -1) EXPECT_NEAR(Q[c], H0 * (293.15 - 400.0), 1e-15);
}
