// End to end: gas in the gaps and radiation between particles from a scene file. A sphere that
// does not touch a hot floor warms through the gas exactly as exp(-H t / C) with H the model's
// conductance, frozen or under dynamic mechanics; without the gas it stays put. Names are
// checked (unknown model, replaying studies refused), and a settled bed in air keeps an exact
// energy balance.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "E2eSupport.h"
#include "thermal/modes/GasGapConductance.h"

using namespace tmdem::e2e;

namespace {

constexpr double kR = 0.001, kGap = 0.05 * kR, kFloor_K = 400.0, kT0_K = 300.0;

// One steel sphere hovering kGap above a 400 K floor (mechanics off: no contact).
SceneBuilder hovering_sphere() {
  return thermal_scene()
      .set("simulation.duration", 20.0)
      .add("particle", particle({0.0, kR + kGap, 0.0}, {{"temperature", kT0_K}}))
      .add("wall", floor_wall({{"temperature", kFloor_K}}))
      .set(tolerances(1.0e-10))
      .set(output("out.h5", 10.0));
}

double final_temperature(const std::string& dir) {
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  return read_doubles(f, "/frames/temperature").back();
}

}  // namespace

TEST(EndToEndGas, AHoveringSphereWarmsThroughTheGasAsTheModelSays) {
  const double k_f = 0.03;
  const double C = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR * 7800.0 * 460.0;
  const double H = tmdem::thermal::surrounding_layer_conductance_W_per_K(
      {kR, std::numeric_limits<double>::infinity(), kGap, 0.0}, k_f, 0.4, 1e-7);
  const double exact = kFloor_K + (kT0_K - kFloor_K) * std::exp(-H * 20.0 / C);
  ASSERT_GT(exact - kT0_K, 1.0);  // the gas matters

  const auto dir = scratch_dir("gas_hover");
  write_file(dir + "/s.toml", hovering_sphere().set({{"effects.gas_conduction", true},
                                                     {"fluid.model", "surrounding_layer"},
                                                     {"fluid.conductivity", k_f}}));
  const auto r = run_tmdem("run s.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NEAR((final_temperature(dir) - kT0_K) / (exact - kT0_K), 1.0, 1e-6);
  const auto s = read_summary(dir + "/s.json");
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);

  // Without the gas nothing reaches it; with Vargas-McCarthy (touching pairs only) neither.
  const std::vector<TomlKeys> variants{
      {{"effects.gas_conduction", false}},
      {{"effects.gas_conduction", true}, {"fluid.model", "vargas_mccarthy"}}};
  for (const TomlKeys& keys : variants) {
    const auto d2 = scratch_dir("gas_hover_off");
    write_file(d2 + "/s.toml", hovering_sphere().set(keys));
    const auto r2 = run_tmdem("run s.toml --quiet", d2);
    ASSERT_EQ(r2.exit_code, 0) << r2.output;
    EXPECT_EQ(final_temperature(d2), kT0_K);
  }
}

TEST(EndToEndGas, UnknownModelAndReplayingStudiesAreRefusedByName) {
  const auto dir = scratch_dir("gas_names");
  write_file(dir + "/s.toml", hovering_sphere().set({{"effects.gas_conduction", true},
                                                     {"fluid.model", "voronoi"}}));
  auto r = run_tmdem("check s.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("fluid.model: must be one of \"vargas_mccarthy\", \"surrounding_layer\", "
                          "\"bahrami\" (got \"voronoi\")"),
            std::string::npos) << r.output;

  // A gas pressure rarefies the surrounding layer's gaps; the touching-pair closed form has none.
  write_file(dir + "/s.toml", hovering_sphere().set({{"effects.gas_conduction", true},
                                                     {"fluid.pressure", 100.0}}));
  r = run_tmdem("check s.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("fluid.pressure: needs model = \"surrounding_layer\""), std::string::npos)
      << r.output;

  // The replaying studies cannot follow near pairs (they record contacts, not positions).
  write_file(dir + "/s.toml", hovering_sphere().set({{"effects.gas_conduction", true},
                                                     {"effects.mechanics", "dynamic"}}));
  r = run_tmdem("study coupling s.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot follow the near pairs of effects.gas_conduction"),
            std::string::npos) << r.output;
}

TEST(EndToEndGas, DynamicRunFollowsNearPairsStepByStep) {
  // The hovering sphere held in place (fixed) under dynamic mechanics: near pairs now come from
  // the packing of every mechanical step, and the answer is the static one.
  const double k_f = 0.03;
  const double C = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR * 7800.0 * 460.0;
  const double H = tmdem::thermal::surrounding_layer_conductance_W_per_K(
      {kR, std::numeric_limits<double>::infinity(), kGap, 0.0}, k_f, 0.4, 1e-7);
  const double duration = 2.0;
  const double exact = kFloor_K + (kT0_K - kFloor_K) * std::exp(-H * duration / C);
  const auto dir = scratch_dir("gas_dynamic");
  write_file(dir + "/s.toml", hovering_sphere()
                                  .set({{"simulation.duration", duration},
                                        {"effects.mechanics", "dynamic"},
                                        {"mechanics.time_step", 0.01},
                                        {"effects.gas_conduction", true},
                                        {"fluid.model", "surrounding_layer"},
                                        {"fluid.conductivity", k_f},
                                        {"output.interval", 1.0}})
                                  .set("particle[0].fixed", true));
  const auto r = run_tmdem("run s.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NEAR((final_temperature(dir) - kT0_K) / (exact - kT0_K), 1.0, 1e-6);
  EXPECT_LT(read_summary(dir + "/s.json")["energy"]["balance_error_rel"].get<double>(), 1e-8);
}

TEST(EndToEndGas, SettledBedInAirWithPairRadiationKeepsAnExactBalance) {
  // The example bed: glass in air, settled, heated from the floor, gas + pair radiation on.
  const auto dir = scratch_dir("gas_bed");
  const auto r = run_tmdem(std::string("run '") + TMDEM_SOURCE_DIR +
                               "/examples/bed_in_air.toml' -o out.h5 --quiet --summary s.json "
                               "--set simulation.duration=5",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
  EXPECT_GT(s["energy"]["boundary_heat_J"].get<double>(), 0.0);
  // Every settle step converged: at its 54th, "nncg" stalled at 1.7x the fall tolerance until
  // it restarted its direction after a stall (NncgSolver::Options::stall_restarts).
  EXPECT_EQ(s["mechanics"]["unconverged_steps"].get<std::int64_t>(), 0);
  EXPECT_EQ(s["mechanics"]["stalled_steps"].get<std::int64_t>(), 0);
}
