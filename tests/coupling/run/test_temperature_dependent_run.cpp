// Temperature-dependent material tables through the whole run (scene -> bridge -> thermal):
// a table of constant values reproduces the constant-property run, a real table closes the
// energy balance, and the explicit update is refused at start.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "coupling/run/CoupledRun.h"
#include "coupling/scene/SceneLoader.h"
#include "support/RunSceneText.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

// A settled column of five steel spheres on a floor at 450 K (Hertz conductances), 20 s.
SceneBuilder column_scene(const TomlKeys& material) {
  return SceneBuilder()
      .set("simulation.duration", 20.0)
      .set("simulation.gravity", {0.0, -9.81, 0.0})
      .set("effects.mechanics", "settle")
      .set(tolerances(1e-10))
      .set(output("out.h5", 20.0))
      .add("material", steel(material))
      .add("generate", column(5, {{"temperature", 300.0}}))
      .add("wall", floor_wall({{"temperature", 450.0}}));
}

TEST(TemperatureDependentRun, ConstantTablesReproduceConstantProperties) {
  const auto constant = run_scene_text(column_scene({}).str(), "constant");
  const auto tables =
      run_scene_text(column_scene({{"conductivity", raw("[[250.0, 50.0], [500.0, 50.0]]")},
                                   {"heat_capacity", raw("[[250.0, 460.0], [500.0, 460.0]]")}})
                         .str(),
                     "tables");
  ASSERT_EQ(constant.exit_code, 0) << constant.summary.message;
  ASSERT_EQ(tables.exit_code, 0) << tables.summary.message;
  for (std::size_t i = 0; i < constant.final_temperature_K.size(); ++i)
    EXPECT_NEAR(tables.final_temperature_K[i], constant.final_temperature_K[i], 1e-7) << i;
  EXPECT_GT(constant.final_temperature_K[0], 300.5);  // heat did flow
  EXPECT_NEAR(tables.summary.energy.final_J, constant.summary.energy.final_J,
              1e-9 * constant.summary.energy.final_J);
}

TEST(TemperatureDependentRun, TablesCloseTheEnergyBalance) {
  const auto outcome =
      run_scene_text(column_scene({{"conductivity", raw("[[250.0, 60.0], [500.0, 40.0]]")},
                                   {"heat_capacity", raw("[[250.0, 420.0], [500.0, 540.0]]")}})
                         .str(),
                     "real");
  ASSERT_EQ(outcome.exit_code, 0) << outcome.summary.message;
  const auto& e = outcome.summary.energy;
  EXPECT_GT(e.boundary_heat_J, 0.1);
  EXPECT_LT(e.balance_error_rel, 1e-9);
}

TEST(TemperatureDependentRun, ExplicitIsRefusedAtStart) {
  const auto outcome =
      run_scene_text(column_scene({{"conductivity", raw("[[250.0, 60.0], [500.0, 40.0]]")}})
                         .set("thermal.integrator", "explicit")
                         .str(),
                     "explicit");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_NE(outcome.summary.message.find("\"cvode\" or \"ida\""), std::string::npos)
      << outcome.summary.message;
}

}  // namespace
}  // namespace tmdem::coupling
