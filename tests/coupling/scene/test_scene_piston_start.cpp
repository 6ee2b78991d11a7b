// A piston's start = "on_bed" (coupling/scene/SceneBuilderBodies.cpp): its plane is moved along
// its normal onto the particles' farthest extent against it, the top of the top sphere; only a
// piston takes the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// 80 steel spheres (radii 0.5 and 0.7 mm) deposited on the floor of an 8 mm box, and a piston
// of normal `normal` through (0.004, 0.05, 0.004), `start` unless empty.
SceneBuilder pressed_deposit(const std::string& start, std::initializer_list<double> normal = {0.0, -1.0, 0.0}) {
  TomlKeys piston = plane_wall({0.004, 0.05, 0.004}, normal,
                               {{"piston", true}, {"mass", 0.01}, {"force", 1.0}});
  if (!start.empty()) piston = with(piston, {{"start", start}});
  return steel_scene()
      .set({{"simulation.dimension", 3}, {"simulation.gravity", {0.0, -9.81, 0.0}}, {"effects.mechanics", "settle"}})
      .add("generate", with(random_fill(80, "{ min = [0.0, 0.0, 0.0], max = [0.008, 0.03, 0.008] }",
                                        {{"radii", {0.0005, 0.0007}}, {"fractions", {0.5, 0.5}}}),
                            {{"kind", "deposit"}}))
      .add("wall", floor_wall())
      .add("wall", piston);
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The particles' farthest extent against the wall's normal: max over them of x . (-n) + r.
double top_against(const Scene& scene, const Wall& wall) {
  double top = -INFINITY;
  const Vec3 up{-wall.normal[0], -wall.normal[1], -wall.normal[2]};
  for (const auto& p : scene.particles) top = std::max(top, dot(p.position_m, up) + p.radius_m);
  return top;
}

}  // namespace

TEST(ScenePistonStart, OnBedPutsThePlaneOnTheTopSphere) {
  const Scene scene = load_scene_text(pressed_deposit("on_bed").str(), "t");
  ASSERT_EQ(scene.walls.size(), 2u);
  const Wall& piston = scene.walls[1];
  // The plane's height is the top of the top sphere: max(y + r).
  const double top_m = top_against(scene, piston);
  EXPECT_GT(top_m, 0.002);  // a real bed, several layers deep
  EXPECT_NEAR(-dot(piston.point_m, piston.normal), top_m, 1e-15);
  // Moved along its normal only.
  EXPECT_EQ(piston.point_m[0], 0.004);
  EXPECT_EQ(piston.point_m[2], 0.004);
  // The given point, the default and start = "point" alike.
  for (const std::string start : {"", "point"}) {
    const Scene as_given = load_scene_text(pressed_deposit(start).str(), "t");
    EXPECT_EQ(as_given.walls[1].point_m, (Vec3{0.004, 0.05, 0.004})) << start;
  }
}

TEST(ScenePistonStart, OnBedFollowsATiltedNormal) {
  // A normal 0.2 rad off the vertical: the plane touches the sphere that reaches farthest
  // against it, and every other sphere is on the domain's side.
  const double tilt = 0.2;
  const Scene scene = load_scene_text(pressed_deposit("on_bed", {std::sin(tilt), -std::cos(tilt), 0.0}).str(), "t");
  const Wall& piston = scene.walls[1];
  double closest_m = INFINITY;
  for (const auto& p : scene.particles)
    closest_m = std::min(closest_m, wall_signed_distance(piston, p.position_m) - p.radius_m);
  EXPECT_NEAR(closest_m, 0.0, 1e-16);
  EXPECT_NEAR(-dot(piston.point_m, piston.normal), top_against(scene, piston), 1e-15);
}

TEST(ScenePistonStart, OnlyAPistonTakesStartAndOnlyItsTwoValues) {
  expect_scene_error(kBaseScene, {"wall[0].start=\"on_bed\""}, {"wall[0].start", "only a piston = true wall"});
  expect_scene_error(pressed_deposit("").str(), {"wall[1].start=\"top\""},
                     {"wall[1].start", "\"point\"", "\"on_bed\"", "top"});
}

}  // namespace tmdem::coupling::test
