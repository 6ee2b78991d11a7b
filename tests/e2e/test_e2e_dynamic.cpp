// End to end: a dynamic run, where contacts close while the particles fall onto a heated floor.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "E2eSupport.h"

using namespace tmdem::e2e;

TEST(EndToEndDynamic, DropOntoHeatedFloorKeepsBalanceBoundsAndHertzConductances) {
  const auto dir = scratch_dir("dynamic_drop");
  const TomlKeys in_copper = {{"material", "copper"}};
  write_file(dir + "/drop.toml",
             copper_drop_scene(0.4)
                 .add("generate", random_fill(12, "{ min = [0.0005, 0.0005, 0.0], max = [0.008, 0.012, 0.0] }",
                                              {{"radius", 0.0008}, {"material", "copper"}, {"temperature", 293.15}}))
                 .add("wall", floor_wall(with(in_copper, {{"temperature", 400.0}})))
                 .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, in_copper))
                 .add("wall", plane_wall({0.0085, 0.0, 0.0}, {-1.0, 0.0, 0.0}, in_copper))
                 .set(tolerances(1.0e-10))
                 .set(output("drop.h5", 0.02)));
  const auto r = run_tmdem("run drop.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  EXPECT_EQ(s["mechanics"]["steps"], 400);
  // The contract's settle block, for a run with no settle phase: nothing judged.
  EXPECT_TRUE(s["settle"]["at_rest"].is_null());
  EXPECT_EQ(s["settle"]["steps"], 0);
  EXPECT_EQ(s["settle"]["ended_by"], "none");
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
  EXPECT_GT(s["energy"]["boundary_heat_J"].get<double>(), 0.0);
  // Re-initialised when contacts close, not every step.
  const long reinit = s["thermal"]["reinitializations"].get<long>();
  EXPECT_GT(reinit, 0);
  EXPECT_LT(reinit, 200);

  H5::H5File f(dir + "/drop.h5", H5F_ACC_RDONLY);
  for (double T : read_doubles(f, "/frames/temperature")) {
    ASSERT_GE(T, 293.15 - 1e-6);
    ASSERT_LE(T, 400.0 + 1e-6);
  }
  const auto offset = read_ints(f, "/frames/contact_offset");
  EXPECT_EQ(offset.front(), 0);
  EXPECT_GT(offset.back(), offset[1]);  // contacts appeared during the run
  // Every stored conductance is the Hertz law of the stored force.
  const auto pair = read_ints(f, "/contacts/pair");
  const auto F = read_doubles(f, "/contacts/normal_force");
  const auto H = read_doubles(f, "/contacts/conductance");
  const auto radius = read_doubles(f, "/particles/radius");
  const double E = 1.2e11, nu = 0.34, k = 400.0;
  for (std::size_t c = 0; c < F.size(); ++c) {
    const double R1 = radius[std::size_t(pair[2 * c])];
    const bool wall = pair[2 * c + 1] < 0;
    const double R_star = wall ? R1 : 1.0 / (1.0 / R1 + 1.0 / radius[std::size_t(pair[2 * c + 1])]);
    const double E_star = E / (2.0 * (1.0 - nu * nu));
    const double expected = 2.0 * k * std::cbrt(3.0 * F[c] * R_star / (4.0 * E_star));
    if (wall && pair[2 * c + 1] != -1) {
      EXPECT_EQ(H[c], 0.0);  // side walls are adiabatic
    } else {
      EXPECT_NEAR(H[c], expected, 1e-12 * expected + 1e-300) << "contact " << c;
    }
  }
}
