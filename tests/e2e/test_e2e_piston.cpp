// End to end: a piston's place in the result file (/frames/wall_position) and across a restart.
// A free piston under a constant force follows x = F t^2 / (2 m) exactly (theta = 1/2, see
// tests/mechanics/test_piston.cpp), and every frame records it there; a settled bed restarted
// from its checkpoint keeps the piston where settling left it (its gas gaps included), so it
// ends where the uninterrupted run ends; with mechanics "off" a piston is refused.
#include <gtest/gtest.h>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

constexpr double kPistonY = 0.01, kMass = 0.02, kForce = 0.01;  // m, kg, N

// A piston facing down (-y) from y = 1 cm, pushed by kForce, with no gravity; one sphere at the
// origin keeps the scene non-empty and is far below the piston's travel (0.6 mm in 0.05 s).
std::string free_piston_scene() {
  return thermal_scene()
      .set({{"simulation.duration", 0.05},
            {"simulation.gravity", {0.0, 0.0, 0.0}},
            {"effects.mechanics", "dynamic"}})
      .set(output("out.h5", 0.01))
      .add("particle", particle({0.0, 0.0, 0.0}))
      .add("wall", floor_wall({{"point", {0.0, -0.001, 0.0}}}))
      .add("wall", plane_wall({0.0, kPistonY, 0.0}, {0.0, -1.0, 0.0},
                              {{"piston", true}, {"mass", kMass}, {"force", kForce}}))
      .str();
}

// One sphere on a hot floor under a cold piston of 10 g pressed by 1 N that starts 0.5 mm above
// it and comes to rest on it while settling; gas conducts across the gaps (surrounding layer).
SceneBuilder settled_piston_scene(double duration_s) {
  return thermal_scene()
      .set({{"simulation.duration", duration_s},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", "settle"},
            {"effects.gas_conduction", true},
            {"fluid.model", "surrounding_layer"},
            {"fluid.conductivity", 0.026}})
      .set(tolerances(1e-10))
      .set(output("out.h5", 0.5))
      .set("output.checkpoint_interval", 1.0)
      .add("particle", particle({0.0, 0.001, 0.0}, {{"temperature", 325.0}}))
      .add("wall", floor_wall({{"temperature", 350.0}}))
      .add("wall", plane_wall({0.0, 0.0025, 0.0}, {0.0, -1.0, 0.0},
                              {{"temperature", 300.0}, {"piston", true}, {"mass", 0.01},
                               {"force", 1.0}}));
}

}  // namespace

TEST(EndToEndPiston, ResultFileRecordsThePistonTrajectory) {
  const auto dir = scratch_dir("piston_frames");
  write_file(dir + "/s.toml", free_piston_scene());
  const auto r = run_tmdem("run s.toml --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  const auto times = read_doubles(f, "/frames/time");
  std::vector<hsize_t> dims;
  const auto walls = read_doubles(f, "/frames/wall_position", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{times.size(), 2, 3}));
  ASSERT_EQ(times.size(), 6u);
  const double a = kForce / kMass;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double* floor = &walls[6 * k];
    const double* piston = &walls[6 * k + 3];
    EXPECT_EQ(floor[0], 0.0);
    EXPECT_EQ(floor[1], -0.001);  // a wall without a piston stays
    const double travel = 0.5 * a * times[k] * times[k];
    EXPECT_NEAR(piston[1], kPistonY - travel, 1e-12 * kPistonY) << "t = " << times[k];
    EXPECT_EQ(piston[0], 0.0);
    EXPECT_EQ(piston[2], 0.0);
  }
  EXPECT_GT(kPistonY - walls[6 * 5 + 4], 6e-4);  // it did move
}

TEST(EndToEndPiston, SettledPistonRestartsWhereSettlingLeftIt) {
  const auto full = scratch_dir("piston_full");
  const auto part = scratch_dir("piston_part");
  write_file(full + "/s.toml", settled_piston_scene(2.0));
  write_file(part + "/s.toml", settled_piston_scene(2.0));
  ASSERT_EQ(run_tmdem("run s.toml --quiet", full).exit_code, 0);
  auto r = run_tmdem("run s.toml --quiet --set simulation.duration=1.0", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("run s.toml --quiet --restart out.checkpoint.h5", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  H5::H5File a(full + "/out.h5", H5F_ACC_RDONLY), b(part + "/out.h5", H5F_ACC_RDONLY);
  const auto wa = read_doubles(a, "/frames/wall_position"), wb = read_doubles(b, "/frames/wall_position");
  ASSERT_EQ(wa.size(), wb.size());
  EXPECT_EQ(wa, wb);
  // The piston came down onto the sphere (top at 2 mm) while settling, and stays there.
  const double piston_y = wa[4];
  EXPECT_LT(piston_y, 0.002 + 1e-6);
  EXPECT_GT(piston_y, 0.002 - 1e-5);
  for (std::size_t k = 0; k < wa.size() / 6; ++k) EXPECT_EQ(wa[6 * k + 4], piston_y);
  const auto Ta = read_doubles(a, "/frames/temperature"), Tb = read_doubles(b, "/frames/temperature");
  ASSERT_EQ(Ta.size(), Tb.size());
  // The restart integrates from the same state over the same gaps: the same temperatures (the
  // scene's piston height 0.5 mm higher would have given the gas another conductance).
  for (std::size_t i = 0; i < Ta.size(); ++i) EXPECT_NEAR(Ta[i], Tb[i], 1e-9) << i;
}

TEST(EndToEndPiston, PistonWithoutMechanicsIsRefused) {
  const auto dir = scratch_dir("piston_off");
  write_file(dir + "/s.toml", settled_piston_scene(1.0).set("effects.mechanics", "off"));
  const auto r = run_tmdem("run s.toml --quiet", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("piston"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("needs effects.mechanics = \"settle\" or \"dynamic\""), std::string::npos)
      << r.output;
}
