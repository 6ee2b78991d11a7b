// --set KEY=VALUE overrides.
#include <gtest/gtest.h>

#include <string>

#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

TEST(SceneOverrides, NumbersArraysAndBooleans) {
  const Scene scene = load_scene_text(
      kBaseScene, "t",
      {"simulation.duration=2.5", "simulation.gravity=[0, -9.81, 0]", "output.contacts=false",
       "simulation.seed=42", "mechanics.time_step = 1e-4"});
  EXPECT_EQ(scene.duration_s, 2.5);
  EXPECT_EQ(scene.gravity_m_per_s2[1], -9.81);
  EXPECT_FALSE(scene.output.contacts);
  EXPECT_EQ(scene.seed, 42u);
  EXPECT_EQ(scene.mechanics.time_step_s, 1e-4);
}

TEST(SceneOverrides, BareWordIsAString) {
  const Scene scene = load_scene_text(
      kBaseScene, "t",
      {"thermal.integrator=explicit", "thermal.linear_solver=\"pcg\"", "output.file=out/run 1.h5"});
  EXPECT_EQ(scene.thermal.integrator, "explicit");
  EXPECT_EQ(scene.thermal.linear_solver, thermal::LinearSolverKind::Pcg);
  EXPECT_EQ(scene.output.file, "out/run 1.h5");
}

TEST(SceneOverrides, LaterOverrideWins) {
  const Scene scene =
      load_scene_text(kBaseScene, "t", {"thermal.integrator=ida", "thermal.integrator=cvode"});
  EXPECT_EQ(scene.thermal.integrator, "cvode");
}

TEST(SceneOverrides, IndexedArrayOfTables) {
  const Scene scene = load_scene_text(kBaseScene, "t", {"material[1].conductivity=2.5"});
  EXPECT_EQ(scene.materials[1].conductivity_W_per_mK, 2.5);
  EXPECT_EQ(scene.materials[0].conductivity_W_per_mK, 50.0);
  expect_scene_error(kBaseScene, {"material[2].conductivity=2.5"},
                     {"--set material[2].conductivity=2.5", "material[2] does not exist",
                      "2 [[material]] entries"});
  expect_scene_error(kBaseScene, {"material.conductivity=2.5"},
                     {"material", "array of tables", "material[0].name"});
}

TEST(SceneOverrides, UnknownKeyIsAnError) {
  expect_scene_error(kBaseScene, {"thermal.integratr=ida"},
                     {"--set thermal.integratr=ida", "unknown key thermal.integratr",
                      "did you mean integrator", "valid keys of thermal: integrator"});
  expect_scene_error(kBaseScene, {"thermals.integrator=ida"},
                     {"unknown key thermals", "at the top level"});
  expect_scene_error(kBaseScene, {"material[0].colour=red"}, {"unknown key material[0].colour"});
  expect_scene_error(kBaseScene, {"simulation.duration.value=1"},
                     {"simulation.duration is a value, not a table"});
}

TEST(SceneOverrides, MalformedOverride) {
  expect_scene_error(kBaseScene, {"simulation.duration"}, {"expected KEY=VALUE"});
  expect_scene_error(kBaseScene, {"=3"}, {"malformed key"});
  expect_scene_error(kBaseScene, {"simulation..duration=3"}, {"malformed key"});
  expect_scene_error(kBaseScene, {"simulation.gravity=[0, 1"},
                     {"--set simulation.gravity=[0, 1", "not a valid TOML value"});
}

TEST(SceneOverrides, MissingSectionIsCreated) {
  const Scene scene = load_scene_text(kBaseScene, "t",
                                      {"effects.convection=true", "convection.coefficient=30"});
  EXPECT_TRUE(scene.effects.on("convection"));
  EXPECT_EQ(scene.heat_modes.find("convection", "coefficient").value(), 30.0);
}

TEST(SceneOverrides, BadValueIsLocatedAtTheOverride) {
  expect_scene_error(kBaseScene, {"thermal.integrator=rk4"},
                     {"--set thermal.integrator: thermal.integrator: must be one of"});
}

TEST(SceneOverrides, ResolvedTomlHoldsOverrides) {
  const Scene scene = load_scene_text(kBaseScene, "t", {"thermal.integrator=explicit"});
  EXPECT_NE(scene.resolved_toml.find("integrator = \"explicit\""), std::string::npos)
      << scene.resolved_toml;
  // The resolved text is itself a valid scene that gives the same result.
  const Scene again = load_scene_text(scene.resolved_toml, "resolved");
  EXPECT_EQ(again.thermal.integrator, "explicit");
  EXPECT_EQ(again.particles.size(), scene.particles.size());
  EXPECT_EQ(again.resolved_toml, scene.resolved_toml);
}

}  // namespace
}  // namespace tmdem::coupling::test
