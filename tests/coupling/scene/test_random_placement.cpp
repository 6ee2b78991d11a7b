// Random placement: inside the box, no overlaps, reproducible, radius classes by fraction.
#include <gtest/gtest.h>

#include <random>

#include "mechanics/model/ParticleSet.h"
#include "coupling/scene/RandomPlacement.h"
#include "mechanics/detection/TouchingPairs.h"

using namespace tmdem::mechanics;
using namespace tmdem::coupling;
using Eigen::Vector3d;

TEST(RandomPlacement, InsideBoxWithoutOverlap3D) {
  const Vector3d lo(-0.01, 0.0, 0.0), hi(0.01, 0.02, 0.01);
  const auto p = place_random(500, lo, hi, {0.001, 0.0005}, {0.4, 0.6}, 42, 3);
  ASSERT_EQ(p.positions.size(), 500u);
  ParticleSet set;
  for (std::size_t i = 0; i < 500; ++i) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p.positions[i][a] - p.radii[i], lo[a]);
      EXPECT_LE(p.positions[i][a] + p.radii[i], hi[a]);
    }
    set.add(p.positions[i], p.radii[i], 1.0, 0);
  }
  EXPECT_TRUE(find_overlaps(set, 0.0).empty());
  // Class sizes: 40 % of 500 = 200 of the first radius, ids 0..199.
  for (std::size_t i = 0; i < 500; ++i) EXPECT_EQ(p.radii[i], i < 200 ? 0.001 : 0.0005) << i;
}

TEST(RandomPlacement, ReproducibleAndSeedDependent) {
  const Vector3d lo(0, 0, 0), hi(0.01, 0.01, 0.01);
  const auto a = place_random(50, lo, hi, {0.0005}, {1.0}, 3, 3);
  const auto b = place_random(50, lo, hi, {0.0005}, {1.0}, 3, 3);
  const auto c = place_random(50, lo, hi, {0.0005}, {1.0}, 4, 3);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_NE(a.positions, c.positions);
  // The first draw is fixed by the standard: mt19937_64 seeded with 3, our own mapping.
  std::mt19937_64 rng(3);
  const double expected_x = 0.0005 + uniform_unit(rng()) * (0.01 - 0.001);
  EXPECT_EQ(a.positions[0].x(), expected_x);
  // mt19937_64's 10000th output for the default seed is fixed by the standard.
  std::mt19937_64 standard;
  standard.discard(9999);
  EXPECT_EQ(standard(), 9981545732273789042ull);
}

TEST(RandomPlacement, TwoDimensionalStaysInPlane) {
  const auto p = place_random(300, Vector3d(0, 0, -1), Vector3d(0.1, 0.1, 1), {0.001, 0.0015},
                              {0.5, 0.5}, 1, 2);
  for (const auto& x : p.positions) EXPECT_EQ(x.z(), 0.0);
  ParticleSet set;
  for (std::size_t i = 0; i < p.radii.size(); ++i) set.add(p.positions[i], p.radii[i], 1.0, 0);
  EXPECT_TRUE(find_overlaps(set, 0.0).empty());
}

TEST(RandomPlacement, ThrowsWhenTheBoxIsTooSmall) {
  EXPECT_THROW(place_random(1000, Vector3d(0, 0, 0), Vector3d(0.01, 0.01, 0.01), {0.001}, {1.0},
                            1, 3, 2000),
               std::runtime_error);
  EXPECT_THROW(place_random(1, Vector3d(0, 0, 0), Vector3d(0.001, 0.01, 0.01), {0.001}, {1.0}, 1, 3),
               std::invalid_argument);
  EXPECT_THROW(place_random(1, Vector3d(0, 0, 0), Vector3d(0.1, 0.1, 0.1), {0.001}, {1.0, 2.0}, 1, 3),
               std::invalid_argument);
}

// A box 1e43 cells wide (found by the scene fuzzer): refused as too large, its cell count taken
// in floating point (an int cast of it was undefined, and in practice gave one cell).
TEST(RandomPlacement, RefusesABoxOfMoreCellsThanAnIntHolds) {
  try {
    place_random(1, Vector3d(0, 0, 0), Vector3d(1e40, 0.1, 0.1), {0.001}, {1.0}, 1, 3);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("box too large"), std::string::npos) << e.what();
  }
}

// Several generators fill one box: the spheres of `avoid` are kept clear of, and an `avoid`
// set that touches nothing changes nothing.
TEST(RandomPlacement, KeepsClearOfEarlierSpheres) {
  const Eigen::Vector3d lo(0, 0, 0), hi(0.02, 0.02, 0.02);
  const auto first = place_random(150, lo, hi, {5e-4, 1e-3}, {0.5, 0.5}, 1, 3);
  const auto second = place_random(150, lo, hi, {5e-4, 1e-3}, {0.5, 0.5}, 2, 3, first);
  int overlaps_without = 0;
  const auto blind = place_random(150, lo, hi, {5e-4, 1e-3}, {0.5, 0.5}, 2, 3);
  for (std::size_t a = 0; a < first.radii.size(); ++a) {
    for (std::size_t b = 0; b < second.radii.size(); ++b) {
      const double reach = first.radii[a] + second.radii[b];
      EXPECT_GE((first.positions[a] - second.positions[b]).norm(), reach) << a << " " << b;
      if ((first.positions[a] - blind.positions[b]).norm() < reach) ++overlaps_without;
    }
  }
  EXPECT_GT(overlaps_without, 0);  // the check above can fail
  RandomPlacement far;
  far.positions = {Eigen::Vector3d(1.0, 1.0, 1.0)};
  far.radii = {1e-3};
  const auto same = place_random(150, lo, hi, {5e-4, 1e-3}, {0.5, 0.5}, 2, 3, far);
  EXPECT_EQ(same.positions, blind.positions);
}
