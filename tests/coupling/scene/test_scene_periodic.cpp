// [periodic]: the periods reach the scene and the mechanics; particles outside a period are
// wrapped into it at load; every bad key or value is refused naming it.
#include <gtest/gtest.h>

#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// The base scene's two touching spheres (x = 0 and 2 mm, radius 1 mm) and floor, periodic
// along x and z with periods of 6 mm.
SceneBuilder periodic_scene() {
  return base_scene().set("periodic.x", {-0.001, 0.005}).set("periodic.z", {-0.003, 0.003});
}

TEST(ScenePeriodic, PeriodsReachTheSceneAndTheMechanics) {
  const Scene scene = load_scene_text(periodic_scene().str(), "test.toml");
  EXPECT_TRUE(scene.periodic.any());
  EXPECT_TRUE(scene.periodic.axis[0]);
  EXPECT_FALSE(scene.periodic.axis[1]);
  EXPECT_TRUE(scene.periodic.axis[2]);
  EXPECT_EQ(scene.periodic.low_m[0], -0.001);
  EXPECT_EQ(scene.periodic.high_m[2], 0.003);
  const auto particles = make_particle_set(scene);
  EXPECT_TRUE(particles.box.along(0));
  EXPECT_FALSE(particles.box.along(1));
  EXPECT_DOUBLE_EQ(particles.box.length(2), 0.006);
  // No [periodic]: no periodic axis.
  EXPECT_FALSE(load_scene_text(kBaseScene, "test.toml").periodic.any());
  EXPECT_FALSE(make_particle_set(load_scene_text(kBaseScene, "test.toml")).box.any());
}

TEST(ScenePeriodic, ParticlesOutsideAPeriodAreWrappedIntoIt) {
  // x = 0.0065 is 1.5 mm past max = 0.005: wrapped to 0.0005.
  const Scene scene = load_scene_text(
      periodic_scene().add("particle", particle({0.0065, 0.004, 0.0})).str(), "test.toml");
  ASSERT_EQ(scene.particles.size(), 3u);
  EXPECT_NEAR(scene.particles[2].position_m[0], 0.0005, 1e-15);
  EXPECT_EQ(scene.particles[2].position_m[1], 0.004);  // y is open
}

TEST(ScenePeriodic, AnOverlapAcrossTheBoundaryIsRefused) {
  // x = 0.0045 is 1.5 mm from x = 0 round the boundary (period 6 mm): the spheres overlap.
  expect_scene_error(periodic_scene().add("particle", particle({0.0045, 0.001, 0.0})).str(),
                     {"particles 0 and 2", "overlap"});
}

TEST(ScenePeriodic, BadKeysAndValuesAreRefused) {
  expect_scene_error(periodic_scene().set("periodic.w", {0.0, 1.0}).str(),
                     {"periodic.w", "unknown key", "x, y, z"});
  expect_scene_error(periodic_scene().set("periodic.x", {0.005, -0.001}).str(),
                     {"test.toml:", "periodic.x", "max must be > min"});
  expect_scene_error(periodic_scene().set("periodic.x", {0.0, 0.003, 0.006}).str(),
                     {"periodic.x", "expected [min, max], 2 numbers (got 3)"});
  expect_scene_error(periodic_scene().set("periodic.x", 0.006).str(),
                     {"periodic.x", "expected an array of numbers"});
  expect_scene_error(periodic_scene().set("periodic.x", {0.0, 0.004}).str(),
                     {"periodic.x", "the period 0.004 m is shorter than", "= 0.0042"});
  expect_scene_error(periodic_scene().set("simulation.dimension", 2).str(),
                     {"periodic.z", "cannot be periodic along z"});
  // The floor's normal is y: periodic along y crosses it.
  expect_scene_error(periodic_scene().set("periodic.y", {0.0, 0.006}).str(),
                     {"periodic.y", "wall[0] crosses the periodic axis y"});
  expect_scene_error(
      periodic_scene().add("wall", {{"shape", "cylinder"}, {"point", {0.0, 0.0, 0.0}},
                                    {"axis", {0.0, 1.0, 0.0}}, {"radius", 0.01},
                                    {"material", "steel"}}).str(),
      {"periodic.x", "wall[1] crosses the periodic axis x"});
  expect_scene_error("periodic = 3\n" + kBaseScene, {"periodic", "table"});
}

}  // namespace
}  // namespace tmdem::coupling::test
