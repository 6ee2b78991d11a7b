// [[wall]] shape = "cylinder" from the scene: keys, overlap check, and contact conduction with an
// isothermal cylinder against the closed-form exponential.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"
#include "thermal/integrators/IntegratorRegistry.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

constexpr double kCylinderRadius = 0.004;  // m

TomlKeys vertical_cylinder(const TomlKeys& changes = {}) {
  return with({{"shape", "cylinder"},
               {"point", {0.0, 0.0, 0.0}},
               {"axis", {0.0, 1.0, 0.0}},
               {"radius", kCylinderRadius},
               {"material", "steel"}},
              changes);
}

std::string load_error(const std::string& text) {
  try {
    load_scene_text(text, "cylinder");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(CylinderWallScene, KeysAreChecked) {
  const auto base = thermal_scene().add("particle", particle({0.0, 0.0, 0.0}));
  EXPECT_NE(load_error(SceneBuilder(base).add("wall", vertical_cylinder({{"normal", {0.0, 1.0, 0.0}}})).str())
                .find("wall[0].normal"),
            std::string::npos);
  EXPECT_NE(load_error(SceneBuilder(base).add("wall", floor_wall({{"radius", 0.01}})).str())
                .find("only a shape = \"cylinder\""),
            std::string::npos);
  auto no_radius = vertical_cylinder();
  no_radius.erase(std::remove_if(no_radius.begin(), no_radius.end(),
                                 [](const auto& kv) { return kv.first == "radius"; }),
                  no_radius.end());
  EXPECT_NE(load_error(SceneBuilder(base).add("wall", no_radius).str()).find("wall[0].radius"),
            std::string::npos);
  EXPECT_NE(load_error(SceneBuilder(base).set("simulation.dimension", 2).add("wall", vertical_cylinder()).str())
                .find("needs simulation.dimension = 3"),
            std::string::npos);
  // A particle poking through the cylinder overlaps it.
  EXPECT_NE(load_error(thermal_scene()
                           .add("particle", particle({kCylinderRadius - 0.0005, 0.0, 0.0}))
                           .add("wall", vertical_cylinder())
                           .str())
                .find("wall[0] overlap"),
            std::string::npos);
}

// One particle touching an isothermal cylinder from inside, one on the axis touching nothing:
// the first relaxes as T_w + (T0 - T_w) exp(-H t / C), the second keeps its temperature.
TEST(CylinderWallScene, IsothermalCylinderHeatsTheParticleTouchingIt) {
  const double Tw = 350.0, T0 = 300.0, H = 1e-3;
  const auto text = thermal_scene()
                        .add("particle", particle({kCylinderRadius - 0.001, 0.0, 0.0}, {{"temperature", T0}}))
                        .add("particle", particle({0.0, 0.0, 0.0}, {{"temperature", T0}}))
                        .add("wall", vertical_cylinder({{"temperature", Tw}}))
                        .str();
  const auto scene = load_scene_text(text, "cylinder");
  std::ostringstream sink;
  ProgressReporter progress(sink, true, false);
  auto problem = build_frozen_thermal_problem(scene, progress);
  const auto& net = problem.system->network();
  ASSERT_EQ(net.wall_edge_count(), 1u);
  EXPECT_EQ(net.wall_node[0], 0);
  const double k = H / net.heat_capacity_J_per_K[0];
  thermal::IntegratorSettings settings;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance_K = 1e-10;
  settings.max_temperature_K = Tw;
  auto cvode = thermal::make_thermal_integrator("cvode", *problem.system, settings);
  cvode->initialize(0.0, problem.T0_K);
  for (double t : {1.0, 10.0, 40.0}) {
    cvode->advance_to(t);
    EXPECT_NEAR(cvode->temperatures_K()[0], Tw + (T0 - Tw) * std::exp(-k * t), 1e-6) << "t = " << t;
    EXPECT_EQ(cvode->temperatures_K()[1], T0);
  }
}

}  // namespace
}  // namespace tmdem::coupling
