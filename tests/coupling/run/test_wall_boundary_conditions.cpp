// Wall boundary conditions: an imposed heat flux (shared by conductance) and wall temperatures
// that follow a table in time, against exact energy accounting and closed-form solutions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

#include "coupling/run/CoupledRun.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"
#include "support/ScratchDir.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

ProgressReporter quiet_progress() {
  static std::ostringstream sink;
  return ProgressReporter(sink, true, false);
}

std::string scratch(const std::string& name) {
  return tmdem::test::scratch_folder("tmdem_wall_bc_", name);
}

// A 3 x 2 x 2 lattice on a floor with an imposed flux, every other boundary adiabatic: all the
// heat that enters is flux x area x time, and it stays in the particles.
TEST(WallFlux, InsulatedBedGainsFluxTimesAreaTimesTime) {
  const double flux = 2500.0, area = 3.0e-5, duration = 40.0;  // W/m^2, m^2, s: P = 75 mW
  for (const char* integrator : {"cvode", "ida", "explicit"}) {
    const auto text = thermal_scene()
                          .set("simulation.duration", duration)
                          .set("thermal.integrator", integrator)
                          .set(tolerances(1e-9))
                          .set(output("flux.h5", 10.0))
                          .add("generate", lattice({3, 2, 2}))
                          .add("wall", floor_wall({{"heat_flux", flux}, {"heat_flux_area", area}}))
                          .str();
    const auto scene = load_scene_text(text, "flux");
    RunOptions options;
    const auto dir = scratch(std::string("flux_") + integrator);
    options.output_path = dir + "/flux.h5";
    options.quiet = true;
    std::ostringstream log;
    const auto outcome = run_scene(scene, options, log);
    ASSERT_EQ(outcome.exit_code, 0) << log.str();
    const auto& e = outcome.summary.energy;
    const double expected = flux * area * duration;
    EXPECT_NEAR(e.boundary_heat_J, expected, 1e-9 * expected) << integrator;
    EXPECT_NEAR(e.final_J - e.initial_J, expected, 1e-9 * expected) << integrator;
  }
}

// The power is shared among the wall's contacts in proportion to their conductance, and its
// Jacobian is exactly zero.
TEST(WallFlux, SharedByConductance) {
  thermal::ThermalNetwork net;
  net.resize_nodes(4);
  for (auto& C : net.heat_capacity_J_per_K) C = 0.01;
  net.flux_wall_power_W = {0.6, -0.2};
  net.add_flux_edge(0, 0, 1e-3);
  net.add_flux_edge(1, 0, 2e-3);
  net.add_flux_edge(2, 0, 3e-3);
  net.add_flux_edge(3, 1, 5e-3);
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> modes;
  modes.push_back(thermal::make_heat_transfer_mode("wall_flux", {}));
  thermal::ThermalSystem system(net, std::move(modes));
  std::vector<double> q(4), T{300.0, 310.0, 320.0, 330.0};
  double boundary = 0.0;
  ASSERT_TRUE(system.heat_flow(T, q, boundary));
  EXPECT_DOUBLE_EQ(q[0], 0.1);
  EXPECT_DOUBLE_EQ(q[1], 0.2);
  EXPECT_DOUBLE_EQ(q[2], 0.3);
  EXPECT_DOUBLE_EQ(q[3], -0.2);
  EXPECT_DOUBLE_EQ(boundary, 0.4);
  thermal::JacobianEvaluation J;
  system.evaluate_jacobian(T, J);
  for (double d : J.diagonal_W_per_K) EXPECT_EQ(d, 0.0);
}

// One particle touching a wall whose temperature ramps: C dT/dt = H (a + b t - T) has
// T(t) = a + b t - b / k + (T0 - a + b / k) exp(-k t), k = H / C, until the table ends at t1;
// after it the wall holds a + b t1 (clamped) and T relaxes exponentially towards it.
TEST(WallTemperatureTable, SingleParticleFollowsRampExactly) {
  const double a = 300.0, b = 2.0, t1 = 30.0, T0 = 290.0, H = 1e-3;  // K, K/s, s, K, W/K
  std::ostringstream table;
  table << "[[0.0, " << a << "], [" << t1 << ", " << a + b * t1 << "]]";
  for (const char* integrator : {"cvode", "ida"}) {
    const auto text = thermal_scene()
                          .set("simulation.duration", 60.0)
                          .add("particle", particle({0.0, 0.001, 0.0}, {{"temperature", T0}}))
                          .add("wall", floor_wall({{"temperature", raw(table.str())}}))
                          .str();
    const auto scene = load_scene_text(text, "ramp");
    auto progress = quiet_progress();
    auto problem = build_frozen_thermal_problem(scene, progress);
    ASSERT_EQ(problem.system->network().wall_edge_count(), 1u);
    const double C = problem.system->network().heat_capacity_J_per_K[0];
    const double k = H / C;
    thermal::IntegratorSettings settings;
    settings.relative_tolerance = 1e-11;
    settings.absolute_tolerance_K = 1e-11;
    settings.max_temperature_K = a + b * t1;
    settings.stop_at_each_time = true;  // do not step past the kink at t1
    auto integ = thermal::make_thermal_integrator(integrator, *problem.system, settings);
    integ->initialize(0.0, problem.T0_K);
    const double T_t1 = a + b * t1 - b / k + (T0 - a + b / k) * std::exp(-k * t1);
    for (double t : {5.0, 15.0, 30.0, 45.0, 60.0}) {
      integ->advance_to(t);
      const double exact = t <= t1 ? a + b * t - b / k + (T0 - a + b / k) * std::exp(-k * t)
                                   : a + b * t1 + (T_t1 - a - b * t1) * std::exp(-k * (t - t1));
      // measured: at most 3.0e-8 K at rtol = atol = 1e-11
      EXPECT_NEAR(integ->temperatures_K()[0], exact, 2e-7) << integrator << " t = " << t;
    }
  }
}

TEST(WallSceneKeys, TablesAndFluxesAreChecked) {
  auto scene_with = [](TomlKeys wall) {
    return thermal_scene().add("generate", lattice({1, 1, 1})).add("wall", floor_wall(wall)).str();
  };
  auto message = [&](TomlKeys wall) -> std::string {
    try {
      load_scene_text(scene_with(wall), "walls");
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({{"temperature", raw("[[0.0, 300.0], [0.0, 310.0]]")}}).find("wall[0].temperature"),
            std::string::npos);
  EXPECT_NE(message({{"temperature", raw("[[0.0, -3.0]]")}}).find("> 0 K"), std::string::npos);
  EXPECT_NE(message({{"temperature", raw("[[0.0, 300.0, 1.0]]")}}).find("[t_s, T_K]"), std::string::npos);
  EXPECT_NE(message({{"temperature", 300.0}, {"heat_flux", 10.0}, {"heat_flux_area", 1e-4}})
                .find("not both"),
            std::string::npos);
  EXPECT_NE(message({{"heat_flux", 10.0}}).find("go together"), std::string::npos);
  // A table starting after t = 0 holds its first value before it (clamped).
  const auto scene = load_scene_text(scene_with({{"temperature", raw("[[10.0, 350.0], [20.0, 360.0]]")}}), "ok");
  EXPECT_EQ(scene.walls[0].temperature_K, 350.0);
  EXPECT_EQ(scene.walls[0].temperature_table.size(), 2u);
}

}  // namespace
}  // namespace tmdem::coupling
