// End to end: effects.mechanics = "coupled" (coupling/run/CoupledRunThermoMechanics.cpp). A row
// of five steel spheres between two fixed walls, gravity pushing it against the left one, both
// walls held at T0 + 100 K: the spheres heat up through their contacts, grow by
// alpha (T - T0) at each coupling, and press on the walls with Hertz's forces. Once the row is
// at the walls' temperature the right wall carries F with
//   d(F) + d(F + N m g) + sum_k d(F + k m g; pairs) = 2 N r - L,   d = (F / K)^(2/3),
// r = r0 (1 + alpha 100 K), K = (4/3) E* sqrt(R*) (R* = r at a wall, r/2 between spheres),
// solved here by bisection; the left wall F + N m g. The energy balance stays exact (the
// integrator is re-initialised at each coupling), and every coupling comes to rest.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "E2eSupport.h"
#include "ResultComparison.h"

using namespace tmdem::e2e;

namespace heated_row {  // named: the e2e tests build as one unit

constexpr int kRowCount = 5;
constexpr double kRowRadius = 1e-3, kRowDensity = 7800.0, kYoung = 2.1e11, kPoisson = 0.3;
constexpr double kAlpha = 1.2e-5, kHeating = 100.0, kT0 = 293.15, kRowG = 9.81;

std::string row_scene() {
  std::string s = R"(format = "tmdem-scene-1"
[simulation]
duration = 2000.0
gravity = [-9.81, 0.0, 0.0]
[effects]
mechanics = "coupled"
[mechanics]
normal_law = "hertz"
solver = "nncg_subspace"
coupling_interval = 100.0
tolerance = 1e-9
[output]
file = "out.h5"
interval = 500.0
[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
conductivity = 42.0
heat_capacity = 464.0
thermal_expansion = 1.2e-5
)";
  for (int k = 0; k < kRowCount; ++k)
    s += "[[particle]]\nposition = [" + number((2 * k + 1) * kRowRadius) + ", 0.0, 0.0]\nradius = " +
         number(kRowRadius) + "\nmaterial = \"steel\"\n";
  s += "[[wall]]\npoint = [0.0, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]\nmaterial = \"steel\"\n"
       "temperature = " + number(kT0 + kHeating) + "\n";
  s += "[[wall]]\npoint = [" + number(2 * kRowCount * kRowRadius) +
       ", 0.0, 0.0]\nnormal = [-1.0, 0.0, 0.0]\nmaterial = \"steel\"\ntemperature = " +
       number(kT0 + kHeating) + "\n";
  return s;
}

// The right wall's force of the heated row (see the file comment), N.
double right_wall_force() {
  const double modulus = 1.0 / (2.0 * (1.0 - kPoisson * kPoisson) / kYoung);
  const double r = kRowRadius * (1.0 + kAlpha * kHeating);
  const double weight = kRowDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRowRadius, 3) * kRowG;
  auto overlap = [&](double force, double radius) {
    return std::cbrt(std::pow(force / (4.0 / 3.0 * modulus * std::sqrt(radius)), 2.0));
  };
  auto total = [&](double force) {
    double s = overlap(force, r) + overlap(force + kRowCount * weight, r);
    for (int k = 1; k < kRowCount; ++k) s += overlap(force + k * weight, r / 2);
    return s;
  };
  const double length = 2 * kRowCount * r - 2 * kRowCount * kRowRadius;
  double low = 0.0, high = 1e3;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (low + high);
    (total(mid) < length ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace heated_row

using namespace heated_row;

TEST(EndToEndThermoMechanics, HeatedRowBetweenFixedWallsPressesWithTheHertzForceOfItsGrowth) {
  const auto dir = scratch_dir("thermo_mechanics_row");
  write_file(dir + "/s.toml", row_scene());
  const auto r = run_tmdem("run s.toml --summary s.json --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  const auto& tm = s.at("thermo_mechanics");
  EXPECT_EQ(tm.at("couplings").get<int>(), 20);
  EXPECT_EQ(tm.at("not_at_rest").get<int>(), 0);
  const auto force = tm.at("last_wall_force_N").get<std::vector<double>>();
  ASSERT_EQ(force.size(), 2u);
  const double expected = right_wall_force();  // 10.83 N
  const double weight = kRowDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRowRadius, 3) * kRowG;
  EXPECT_NEAR(force[1], expected, 1e-6 * expected);
  EXPECT_NEAR(force[0], expected + kRowCount * weight, 1e-6 * expected);
  EXPECT_LE(s.at("energy").at("balance_error_rel").get<double>(), 1e-12);
  EXPECT_EQ(s.at("mechanics").at("unconverged_steps").get<int>(), 0);
  EXPECT_EQ(s.at("thermal").at("coupling").get<std::string>(), "restart");  // the scene says nothing
  // Every frame's wall forces in the result file (/frames/wall_force [F, W]): the last is the
  // summary's, and each is the sum of that frame's wall contacts.
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto wall_force = read_doubles(f, "/frames/wall_force", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{5, 2}));  // frames at 0, 500, ..., 2000 s
  EXPECT_EQ(wall_force[8], force[0]);
  EXPECT_EQ(wall_force[9], force[1]);
  const auto offset = read_ints(f, "/frames/contact_offset");
  const auto pair = read_ints(f, "/contacts/pair");
  const auto normal = read_doubles(f, "/contacts/normal_force");
  for (std::size_t frame = 0; frame < 5; ++frame) {
    double sum[2] = {0.0, 0.0};
    for (long long k = offset[frame]; k < offset[frame + 1]; ++k)
      if (pair[2 * k + 1] < 0) sum[-1 - pair[2 * k + 1]] += normal[k];
    EXPECT_EQ(wall_force[2 * frame], sum[0]) << "frame " << frame;
    EXPECT_EQ(wall_force[2 * frame + 1], sum[1]) << "frame " << frame;
  }
}

TEST(EndToEndThermoMechanics, WithoutExpansionTheRowKeepsItsWeightsOnly) {
  // alpha = 0: the couplings re-settle an unchanged row; the left wall carries the row's weight.
  const auto dir = scratch_dir("thermo_mechanics_rigid_row");
  std::string scene = row_scene();
  scene.replace(scene.find("thermal_expansion = 1.2e-5"), 26, "thermal_expansion = 0.0");
  write_file(dir + "/s.toml", scene);
  const auto r = run_tmdem("run s.toml --summary s.json --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  const auto force = s.at("thermo_mechanics").at("last_wall_force_N").get<std::vector<double>>();
  const double weight = kRowDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRowRadius, 3) * kRowG;
  EXPECT_NEAR(force[0], kRowCount * weight, 1e-6 * kRowCount * weight);
  EXPECT_EQ(force[1], 0.0);
  EXPECT_LE(s.at("energy").at("balance_error_rel").get<double>(), 1e-12);
}

TEST(EndToEndThermoMechanics, RestartedCoupledRunIsBitwiseTheUninterruptedOne) {
  // The heated row to 2000 s in one go, and stopped at 1000 s then restarted from the
  // checkpoint (checkpoints every 500 s in both): the same result file, bit for bit, and the same
  // summary (couplings, wall forces, energy) but for wall times.
  const auto full = scratch_dir("thermo_mechanics_full");
  const auto part = scratch_dir("thermo_mechanics_part");
  for (const auto& dir : {full, part}) write_file(dir + "/s.toml", row_scene());
  const std::string common = "run s.toml --quiet -o out.h5 --set output.checkpoint_interval=500 ";
  auto r = run_tmdem(common + "--summary s.json", full);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem(common + "--set simulation.duration=1000", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem(common + "--restart out.checkpoint.h5 --summary s.json", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::size_t compared = 0;
  for (const auto& line : result_differences(full + "/out.h5", part + "/out.h5", &compared))
    ADD_FAILURE() << line;
  EXPECT_GE(compared, 12u);
  EXPECT_EQ(summary_without_wall_times(full + "/s.json"), summary_without_wall_times(part + "/s.json"));
  EXPECT_EQ(read_summary(part + "/s.json").at("thermo_mechanics").at("couplings").get<int>(), 20);
}

TEST(EndToEndThermoMechanics, GrowthUnderRigidContactsIsWarnedOf) {
  const auto dir = scratch_dir("thermo_mechanics_rigid_warning");
  write_file(dir + "/s.toml", row_scene());
  const auto r = run_tmdem("check s.toml --set mechanics.normal_law=\"rigid\"", dir);
  EXPECT_NE(r.output.find("warning: material \"steel\" expands (thermal_expansion 1.2e-05 1/K) under "
                          "mechanics.normal_law = \"rigid\""),
            std::string::npos)
      << r.output;
  EXPECT_EQ(run_tmdem("check s.toml", dir).output.find("expands"), std::string::npos);
}
