// The warning on a deposit laid above its floor (coupling/scene/DepositSupport.h): a box whose
// floor is on no wall drops its bed at the start of the run, by the gap to the wall below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// `count` steel spheres (radii 0.5 and 0.7 mm) deposited in an 8 mm box whose floor is lift_m
// above the floor wall y = 0, mechanics on.
SceneBuilder lifted_deposit(double lift_m, int count = 60) {
  std::ostringstream box;
  box << "{ min = [0.0, " << lift_m << ", 0.0], max = [0.008, 0.03, 0.008] }";
  return steel_scene()
      .set({{"simulation.dimension", 3},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", "settle"}})
      .add("generate", with(random_fill(count, box.str(), {{"radii", {0.0005, 0.0007}}, {"fractions", {0.5, 0.5}}}),
                            {{"kind", "deposit"}}))
      .add("wall", floor_wall());
}

// The lowest sphere's bottom above y = 0, m: how far the bed falls onto the floor wall.
double lowest_bottom_m(const Scene& scene) {
  double lowest = INFINITY;
  for (const auto& p : scene.particles) lowest = std::min(lowest, p.position_m[1] - p.radius_m);
  return lowest;
}

std::string figure(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) out += line + "\n";
  return out;
}

}  // namespace

TEST(DepositSupport, ABoxAboveTheFloorWallIsWarnedOfWithItsGapAndWall) {
  const double lift_m = 0.001;
  const Scene scene = load_scene_text(lifted_deposit(lift_m).str(), "t");
  // The bed lies on the box's floor, so it falls by the lift onto the wall.
  const double fall_m = lowest_bottom_m(scene);
  ASSERT_NEAR(fall_m, lift_m, 1e-12);
  ASSERT_EQ(scene.warnings.size(), 1u);
  const std::string& warning = scene.warnings[0];
  EXPECT_TRUE(contains(warning, "generate[0]")) << warning;
  EXPECT_TRUE(contains(warning, "y = " + figure(lift_m) + " m, which is on no wall")) << warning;
  EXPECT_TRUE(contains(warning, "falls " + figure(fall_m) + " m onto wall[0]")) << warning;
  EXPECT_TRUE(contains(warning, "set the box's floor to y = 0 m")) << warning;
}

TEST(DepositSupport, ABoxOnTheFloorWallOrOnAnEarlierBedIsNot) {
  const Scene on_wall = load_scene_text(lifted_deposit(0.0).str(), "t");
  EXPECT_NEAR(lowest_bottom_m(on_wall), 0.0, 1e-15);
  EXPECT_TRUE(on_wall.warnings.empty()) << joined(on_wall.warnings);
  // A second deposit whose box floor is 2 mm up, on top of a first bed of 200 spheres (about
  // four layers over the 8 x 8 mm floor): its spheres rest on the first ones, none on its
  // box's floor.
  const Scene stacked = load_scene_text(
      lifted_deposit(0.0, 200)
          .add("generate", with(random_fill(20, "{ min = [0.0, 0.002, 0.0], max = [0.008, 0.03, 0.008] }",
                                            {{"radius", 0.0007}}),
                                {{"kind", "deposit"}}))
          .str(),
      "t");
  ASSERT_EQ(stacked.particles.size(), 220u);
  for (std::size_t i = 200; i < stacked.particles.size(); ++i)
    ASSERT_GT(stacked.particles[i].position_m[1] - stacked.particles[i].radius_m, 0.002 + 1e-9) << i;
  EXPECT_TRUE(stacked.warnings.empty()) << joined(stacked.warnings);
  // Mechanics off: nothing falls.
  EXPECT_TRUE(load_scene_text(lifted_deposit(0.001).str(), "t", {"effects.mechanics=\"off\"", "thermal.conductance=\"constant\""}).warnings.empty());
}

TEST(DepositSupport, WithoutAWallBelowTheBedFallsForGood) {
  // The floor wall faces down (n = -y), as a lid would: nothing below holds the bed.
  const Scene scene = load_scene_text(lifted_deposit(0.001).str(), "t", {"wall[0].normal=[0.0, -1.0, 0.0]",
                                                                         "wall[0].point=[0.0, 0.05, 0.0]"});
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_TRUE(contains(scene.warnings[0], "generate[0]")) << scene.warnings[0];
  EXPECT_TRUE(contains(scene.warnings[0], "no wall facing up below it")) << scene.warnings[0];
  EXPECT_TRUE(contains(scene.warnings[0], "add a floor [[wall]] at y = 0.001 m")) << scene.warnings[0];
}

}  // namespace tmdem::coupling::test
