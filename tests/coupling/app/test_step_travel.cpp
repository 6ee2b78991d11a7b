// `tmdem check`'s estimate of the largest travel per mechanics step (coupling/app/StepTravel.h)
// against free fall by hand, and when it warns.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/app/StepTravel.h"
#include "coupling/scene/DefaultScene.h"

namespace tmdem::coupling {
namespace {

constexpr double kG = 9.81;

Scene one_sphere(double bottom_above_floor_m, double floor_tilt_rad) {
  Scene scene;
  scene.effects.mechanics = MechanicsMode::Settle;
  scene.gravity_m_per_s2 = {0.0, -kG, 0.0};
  scene.mechanics.time_step_s = 1e-3;
  scene.mechanics.settle_time_s = 5.0;
  Particle p;
  p.radius_m = 1e-3;
  // Above the origin, where the (possibly tilted) floor passes.
  p.position_m = {0.0, (bottom_above_floor_m + p.radius_m) / std::cos(floor_tilt_rad), 0.0};
  scene.particles.push_back(p);
  Wall floor;
  floor.normal = {std::sin(floor_tilt_rad), std::cos(floor_tilt_rad), 0.0};
  scene.walls.push_back(floor);
  return scene;
}

TEST(StepTravel, FallOntoTheFloorCapsTheSpeed) {
  const StepTravel t = estimate_step_travel(one_sphere(0.1, 0.0));
  EXPECT_NEAR(t.speed_m_per_s, std::sqrt(2 * kG * 0.1), 1e-12);
  EXPECT_NEAR(t.travel_m, 1e-3 * std::sqrt(2 * kG * 0.1), 1e-15);
  EXPECT_EQ(t.smallest_radius_m, 1e-3);
  EXPECT_FALSE(t.too_far());  // settle: 1.4 mm per step against 2 x 1 mm
  Scene dynamic = one_sphere(0.1, 0.0);
  dynamic.effects.mechanics = MechanicsMode::Dynamic;
  dynamic.duration_s = 5.0;
  EXPECT_TRUE(estimate_step_travel(dynamic).too_far());  // dynamic: against 0.5 x 1 mm
}

TEST(StepTravel, TiltedFloorIsReachedAlongGravity) {
  // Distance d to a floor tilted by 60 degrees: the vertical fall onto it is 2 d.
  const double tilt = std::acos(0.5);
  const StepTravel t = estimate_step_travel(one_sphere(0.01, tilt));
  // The sphere is 0.01 m from the floor along its normal; falling vertically it closes
  // cos(tilt) of each metre, so it falls 0.01 / cos(tilt) = 0.02 m.
  const double fall = 0.01 / std::cos(tilt);
  EXPECT_NEAR(t.speed_m_per_s, std::sqrt(2 * kG * fall), 1e-12);
}

TEST(StepTravel, WithoutAFloorTheSpeedGrowsOverTheWholePhase) {
  Scene scene = one_sphere(0.1, 0.0);
  scene.walls.clear();
  EXPECT_NEAR(estimate_step_travel(scene).speed_m_per_s, kG * 5.0, 1e-12);
  scene.effects.mechanics = MechanicsMode::Dynamic;
  scene.duration_s = 0.01;
  const StepTravel t = estimate_step_travel(scene);
  EXPECT_NEAR(t.speed_m_per_s, kG * 0.01, 1e-15);
  EXPECT_FALSE(t.too_far());  // 0.1 mm per step against 0.5 mm
}

// A cylinder across gravity (a drum, a horizontal pipe) is the floor of what lies in it: a sphere
// of 1 mm off the axis of a 15 mm drum falls straight down until its centre is 14 mm from the
// axis, by hand. Along gravity (an upright cylinder) it stops nothing. Before, only plane walls
// were floors, and the drum's spheres were estimated to fall for the whole settle (49 m/s).
TEST(StepTravel, ACylinderAcrossGravityIsAFloor) {
  Scene scene;
  scene.effects.mechanics = MechanicsMode::Settle;
  scene.gravity_m_per_s2 = {0.0, 0.0, -kG};
  scene.mechanics.time_step_s = 1e-3;
  scene.mechanics.settle_time_s = 5.0;
  Particle p;
  p.radius_m = 1e-3;
  p.position_m = {0.002, 0.006, 0.004};
  scene.particles.push_back(p);
  Wall drum;
  drum.cylinder = true;
  drum.normal = {1.0, 0.0, 0.0};
  drum.radius_m = 0.015;
  scene.walls.push_back(drum);
  // The centre stays within 14 mm of the axis: at y = 6 mm it reaches z = -sqrt(14^2 - 6^2) mm.
  const double fall = 0.004 + std::sqrt(0.014 * 0.014 - 0.006 * 0.006);
  EXPECT_NEAR(estimate_step_travel(scene).speed_m_per_s, std::sqrt(2 * kG * fall), 1e-12);
  // Resting on the drum's bottom: no fall.
  scene.particles[0].position_m = {0.002, 0.0, -0.014};
  EXPECT_NEAR(estimate_step_travel(scene).speed_m_per_s, 0.0, 1e-12);
  // Upright: the cylinder is no floor, the sphere falls for the whole settle.
  scene.walls[0].normal = {0.0, 0.0, 1.0};
  EXPECT_NEAR(estimate_step_travel(scene).speed_m_per_s, kG * 5.0, 1e-12);
}

// A sphere resting on the floor with an overlap of round-off (a deposited bed's; the loader
// accepts up to 1e-9 of the radius, here 1e-10 of it) rests: no fall, no speed of its own.
TEST(StepTravel, ARoundOffOverlapWithTheFloorIsResting) {
  Scene scene = one_sphere(-1e-13, 0.0);
  ASSERT_LT(wall_signed_distance(scene.walls[0], scene.particles[0].position_m) - scene.particles[0].radius_m, 0.0);
  EXPECT_EQ(estimate_step_travel(scene).speed_m_per_s, 0.0);
  // Deeper than the loader allows (it would not load): it touches the floor, so it rests too.
  scene = one_sphere(-1e-6, 0.0);
  EXPECT_EQ(estimate_step_travel(scene).speed_m_per_s, 0.0);
}

// A laid bed rests: a particle on something below it that rests does not fall. A column of five
// touching spheres on the floor gets no speed (before, its top sphere was taken to fall 8 mm
// onto the floor); lifted 1 mm off the floor, every sphere falls, the top one 9 mm; a sphere
// beside the grounded column, touching it only at its equator, is held by nothing below it and
// falls its own height.
TEST(StepTravel, ALaidColumnRestsAndALiftedOneFalls) {
  Scene scene = one_sphere(0.0, 0.0);  // radius 1 mm, on the floor y = 0, gravity -y
  const double r = scene.particles[0].radius_m;
  for (int k = 1; k < 5; ++k) {
    Particle p = scene.particles[0];
    p.position_m[1] = r + 2.0 * r * k;
    scene.particles.push_back(p);
  }
  StepTravel t = estimate_step_travel(scene);
  EXPECT_EQ(t.speed_m_per_s, 0.0);
  EXPECT_EQ(t.resting_particles, 5u);
  Scene lifted = scene;
  for (auto& p : lifted.particles) p.position_m[1] += 1e-3;
  t = estimate_step_travel(lifted);
  EXPECT_EQ(t.resting_particles, 0u);
  EXPECT_NEAR(t.speed_m_per_s, std::sqrt(2 * kG * (8 * r + 1e-3)), 1e-12);
  Particle side = scene.particles[2];  // beside the third sphere, touching it at its equator
  side.position_m[0] += 2.0 * r;
  scene.particles.push_back(side);
  t = estimate_step_travel(scene);
  EXPECT_EQ(t.resting_particles, 5u);
  EXPECT_NEAR(t.speed_m_per_s, std::sqrt(2 * kG * 4 * r), 1e-12);
}

TEST(StepTravel, RestingOrStillScenesDoNotWarn) {
  const StepTravel resting = estimate_step_travel(one_sphere(0.0, 0.0));
  EXPECT_EQ(resting.speed_m_per_s, 0.0);
  EXPECT_FALSE(resting.too_far());
  Scene off = one_sphere(0.1, 0.0);
  off.effects.mechanics = MechanicsMode::Off;
  EXPECT_EQ(estimate_step_travel(off).travel_m, 0.0);
  Scene fixed = one_sphere(0.1, 0.0);
  fixed.particles[0].fixed = true;
  EXPECT_EQ(estimate_step_travel(fixed).travel_m, 0.0);
}

// The brief's bad case: 0.1 mm disks falling 1 m onto the floor with h = 1e-3 s reach
// sqrt(2 g 1 m) = 4.43 m/s, 4.43 mm per step, 44 radii: a warning in either mode.
TEST(StepTravel, SmallDisksFallingOneMetreWarn) {
  Scene scene = one_sphere(1.0, 0.0);
  scene.particles[0].radius_m = 1e-4;
  scene.particles[0].position_m = {0.0, 1.0 + 1e-4, 0.0};
  const StepTravel t = estimate_step_travel(scene);
  EXPECT_NEAR(t.travel_m, 1e-3 * std::sqrt(2 * kG * 1.0), 1e-15);
  EXPECT_EQ(t.limit_m(), 2e-4);
  EXPECT_TRUE(t.too_far());
  // The warning's own advice is enough: at h = limit / v it no longer warns.
  scene.mechanics.time_step_s = t.limit_m() / t.speed_m_per_s * (1.0 - 1e-12);
  EXPECT_FALSE(estimate_step_travel(scene).too_far());
}

// The default scene (examples/paper_bed.toml, settle) must not warn: predicted 0.93 mm per step,
// 1.86 r_min; measured 0.70 mm (1.40 r_min) in the run, whose settled packing matched one made
// at a quarter of the step (docs/mechanics.md "Travel per step"). The same fall in a dynamic run warns.
TEST(StepTravel, DefaultSceneDoesNotWarnButItsDynamicTwinDoes) {
  const Scene scene = load_default_scene();
  const StepTravel t = estimate_step_travel(scene);
  EXPECT_GT(t.travel_m, t.smallest_radius_m);  // a real fall, not a trivially quiet scene
  EXPECT_FALSE(t.too_far()) << t.travel_m / t.smallest_radius_m;
  const Scene dynamic = load_default_scene({"effects.mechanics=\"dynamic\"", "simulation.duration=5.0"});
  EXPECT_TRUE(estimate_step_travel(dynamic).too_far());
}

// A piston of mass m pushed by F falls D onto the bed's floor at most: sqrt(2 (F / m + g) D).
TEST(StepTravel, PistonSpeedBoundsTheTravel) {
  Scene scene = one_sphere(0.0, 0.0);  // resting: no travel of its own
  Wall piston;
  piston.point_m = {0.0, 0.025, 0.0};
  piston.normal = {0.0, -1.0, 0.0};
  piston.piston = true;
  piston.piston_mass_kg = 0.002;
  piston.piston_force_N = 0.064;
  scene.walls.push_back(piston);
  const double a = 0.064 / 0.002 + kG;
  const StepTravel t = estimate_step_travel(scene);
  EXPECT_NEAR(t.speed_m_per_s, std::sqrt(2 * a * 0.025), 1e-12);
  // A force pulling it out of the domain, larger than its weight: it never moves in.
  scene.walls.back().piston_force_N = -0.1;
  EXPECT_EQ(estimate_step_travel(scene).speed_m_per_s, 0.0);
}

// The ghost gap is the true gap of two smallest spheres whose linearised gap is 0 after a
// sideways move of one travel: sqrt((2 r)^2 + d^2) - 2 r by Pythagoras. A small travel gives
// about d^2 / (4 r); a travel of many radii gives less than the travel (the small-travel
// formula had put spheres 2.4 m apart after a 0.09 m step).
TEST(StepTravel, GhostGapIsThePythagoreanGapAndNeverExceedsTheTravel) {
  StepTravel t;
  t.smallest_radius_m = 1e-3;
  t.travel_m = 1e-5;
  // The series' next term is d^2 / (4 (2 r)^2) = 6.25e-6 of the first.
  EXPECT_NEAR(t.ghost_gap_m(), 1e-10 / 4e-3, 1e-5 * 1e-10 / 4e-3);
  t.smallest_radius_m = 0.8e-3;
  t.travel_m = 0.09;
  const double centres_m = std::hypot(2 * t.smallest_radius_m, t.travel_m);  // after the move
  EXPECT_NEAR(t.ghost_gap_m(), centres_m - 2 * t.smallest_radius_m, 1e-15);
  EXPECT_GT(t.ghost_gap_m(), t.travel_m - 2 * t.smallest_radius_m);
  EXPECT_LT(t.ghost_gap_m(), t.travel_m);
}

}  // namespace
}  // namespace tmdem::coupling
