// End to end with mechanics: two stacked spheres settle on an adiabatic floor, then exchange heat
// through their Hertz contact, whose force is the top sphere's weight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "E2eSupport.h"

using namespace tmdem::e2e;

TEST(EndToEndHertz, TwoStackedSpheresDecayWithHertzConductanceOfTheWeight) {
  const auto dir = scratch_dir("hertz");
  write_file(dir + "/two.toml",
             steel_scene()
                 .set({{"simulation.duration", 2000.0},
                       {"simulation.dimension", 3},
                       {"simulation.gravity", {0.0, -9.81, 0.0}},
                       {"effects.mechanics", "settle"}})
                 .add("generate", column(2))
                 .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
                 .add("wall", floor_wall())
                 .set("mechanics.tolerance", 1.0e-12)
                 .set(tolerances(1.0e-10))
                 .set(output("two.h5", 100.0)));
  const auto r = run_tmdem("run two.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File f(dir + "/two.h5", H5F_ACC_RDONLY);
  const auto pair = read_ints(f, "/contacts/pair");
  const auto force = read_doubles(f, "/contacts/normal_force");
  const auto H = read_doubles(f, "/contacts/conductance");
  const auto offset = read_ints(f, "/frames/contact_offset");
  const auto mass = read_doubles(f, "/particles/mass");
  const auto C = read_doubles(f, "/particles/heat_capacity");
  const double g = 9.81, r0 = 1e-3, E = 2.1e11, nu = 0.3, k = 50.0;
  ASSERT_EQ(offset[1] - offset[0], 2);  // sphere-sphere and sphere-floor
  double H01 = -1.0;
  for (long long c = offset[0]; c < offset[1]; ++c) {
    if (pair[2 * c + 1] == 1) {  // (0, 1): carries the top sphere's weight
      EXPECT_NEAR(force[c], mass[1] * g, 1e-6 * mass[1] * g);
      const double R_star = r0 / 2.0, E_star = E / (2.0 * (1.0 - nu * nu));
      const double a = std::cbrt(3.0 * mass[1] * g * R_star / (4.0 * E_star));
      EXPECT_NEAR(H[c], 2.0 * k * a, 1e-5 * 2.0 * k * a);
      H01 = H[c];
    } else {  // (0, floor): both weights; adiabatic wall, so no conductance
      EXPECT_EQ(pair[2 * c + 1], -1);
      EXPECT_NEAR(force[c], (mass[0] + mass[1]) * g, 1e-6 * (mass[0] + mass[1]) * g);
      EXPECT_EQ(H[c], 0.0);
    }
  }
  ASSERT_GT(H01, 0.0);
  const auto time = read_doubles(f, "/frames/time");
  const auto T = read_doubles(f, "/frames/temperature");
  for (std::size_t fr = 0; fr < time.size(); ++fr) {
    const double dT = T[2 * fr] - T[2 * fr + 1];
    const double expected = 80.0 * std::exp(-2.0 * H01 * time[fr] / C[0]);
    EXPECT_NEAR(dT, expected, 1e-6 * 80.0) << "t = " << time[fr];
  }
}
