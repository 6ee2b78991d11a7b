// Validation rules of contract section 2 on the scene's syntax: unknown keys (with suggestions),
// wrong types, required and matching format, required duration, refused NaN and infinity,
// integers where floats are expected, switched-off sections and vector shapes. Loading throws
// SceneError and the message names the key path (and the allowed values or range).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "tests/coupling/SceneTestUtil.h"
#include "tests/coupling/scene/SceneRulesText.h"

namespace tmdem::coupling::test {
namespace {

using namespace scene_rules;

TEST(SceneRules, BaseSceneLoads) {
  const Scene scene = load_scene_text(kBaseScene, "test.toml");
  EXPECT_EQ(scene.particles.size(), 2u);
  EXPECT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.walls.size(), 1u);
  EXPECT_EQ(scene.source, "test.toml");
}

TEST(SceneRules, UnknownTopLevelKey) {
  expect_scene_error(kBaseScene + "\nfoo = 1\n", {"foo", "unknown key", "valid keys here:"});
}

TEST(SceneRules, UnknownKeyInSectionSuggestsAndListsValidKeys) {
  expect_scene_error(kBaseScene + "\n[thermal]\nintegratr = \"ida\"\n",
                     {"test.toml:", "thermal.integratr", "did you mean integrator",
                      "integrator, linear_solver, relative_tolerance"});
}

TEST(SceneRules, UnknownKeyInArrayOfTables) {
  expect_scene_error(replaced(kBaseScene, "emissivity = 0.9", "emissivity = 0.9\ncolour = 1"),
                     {"material[1].colour", "unknown key"});
}

TEST(SceneRules, UnknownKeyInInlineTable) {
  expect_scene_error(kBaseScene + "\n[[assign]]\nbox = { min = [0,0,0], max = [1,1,1], "
                                  "maxx = 3 }\ntemperature = 300.0\n",
                     {"assign[0].box.maxx", "unknown key", "min, max"});
}

TEST(SceneRules, WrongTypeNumber) {
  expect_scene_error(replaced(kBaseScene, "duration = 10", "duration = \"ten\""),
                     {"test.toml:4:", "simulation.duration", "expected a number, got a string"});
}

TEST(SceneRules, WrongTypeBoolean) {
  expect_scene_error(kBaseScene, {"effects.conduction=1"},
                     {"effects.conduction", "expected a boolean"});
}

TEST(SceneRules, WrongTypeString) {
  expect_scene_error(kBaseScene, {"thermal.integrator=3"},
                     {"thermal.integrator", "expected a string, got an integer"});
}

TEST(SceneRules, WrongTypeTable) {
  expect_scene_error("thermal = 3\n" + kBaseScene, {"test.toml:1:11: thermal", "expected a table"});
}

TEST(SceneRules, WrongTypeArrayOfTables) {
  expect_scene_error("format = \"tmdem-scene-1\"\nmaterial = 5\n[simulation]\nduration = 1\n",
                     {"material", "expected an array of tables ([[material]])"});
}

TEST(SceneRules, WrongTypeInteger) {
  expect_scene_error(kBaseScene, {"simulation.dimension=3.0"},
                     {"simulation.dimension", "expected an integer"});
}

TEST(SceneRules, FormatRequired) {
  expect_scene_error(replaced(kBaseScene, "format = \"tmdem-scene-1\"", ""),
                     {"format", "required", "tmdem-scene-1"});
}

TEST(SceneRules, FormatMustMatch) {
  expect_scene_error(kBaseScene, {"format=\"tmdem-scene-2\""},
                     {"format", "must be \"tmdem-scene-1\"", "tmdem-scene-2"});
}

TEST(SceneRules, DurationRequired) {
  expect_scene_error(replaced(kBaseScene, "duration = 10", ""),
                     {"simulation.duration", "required key is missing"});
  expect_scene_error(replaced(kBaseScene, "[simulation]\nduration = 10", ""),
                     {"simulation.duration", "required key is missing"});
}

TEST(SceneRules, DurationPositive) {
  expect_scene_error(kBaseScene, {"simulation.duration=0"},
                     {"simulation.duration", "must be > 0", "got 0"});
}

TEST(SceneRules, NaNRefused) {
  expect_scene_error(kBaseScene, {"material[0].density=nan"},
                     {"material[0].density", "finite", "nan"});
}

TEST(SceneRules, InfinityRefused) {
  expect_scene_error(kBaseScene, {"simulation.duration=inf"}, {"simulation.duration", "finite"});
  expect_scene_error(kBaseScene, {"simulation.gravity=[0, -inf, 0]"},
                     {"simulation.gravity[1]", "finite"});
}

TEST(SceneRules, IntegerWhereFloatExpected) {
  const Scene scene = load_scene_text(kBaseScene, "t", {"mechanics.theta=1"});
  EXPECT_DOUBLE_EQ(scene.duration_s, 10.0);
  EXPECT_DOUBLE_EQ(scene.mechanics.theta, 1.0);
}

TEST(SceneRules, SwitchedOffSectionAcceptedAndIgnored) {
  const std::string text = kBaseScene +
                           "\n[convection]\ncoefficient = -5.0\n[radiation]\n"
                           "ambient_temperature = -1.0\n";
  EXPECT_NO_THROW(load_scene_text(text, "t"));
  expect_scene_error(text, {"effects.convection=true"}, {"convection.coefficient", ">= 0"});
  expect_scene_error(text, {"effects.radiation=true"},
                     {"radiation.ambient_temperature", ">= 0"});
  // Still checked for unknown keys and types.
  expect_scene_error(kBaseScene + "\n[convection]\ncoeficient = 5.0\n",
                     {"convection.coeficient", "unknown key"});
  expect_scene_error(kBaseScene + "\n[convection]\ncoefficient = \"high\"\n",
                     {"convection.coefficient", "expected a number"});
  // [mechanics] is ignored when mechanics is off.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                  {"effects.mechanics=off", "thermal.conductance=constant",
                                   "mechanics.time_step=-1"}));
}

TEST(SceneRules, VectorShape) {
  expect_scene_error(kBaseScene, {"particle[0].position=[0, 1]"},
                     {"particle[0].position", "3 numbers", "2 elements"});
  expect_scene_error(kBaseScene, {"particle[0].position=[0, \"a\", 1]"},
                     {"particle[0].position[1]", "expected a number"});
  // In 2D two components are enough (z = 0).
  const Scene scene = load_scene_text(kBaseScene, "t",
                                      {"simulation.dimension=2", "particle[0].position=[0, 0.001]"});
  EXPECT_EQ(scene.particles[0].position_m[2], 0.0);
}

}  // namespace
}  // namespace tmdem::coupling::test
