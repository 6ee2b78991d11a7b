// Geometry-only detection: hand-made cases with known answers, and agreement with an
// all-pairs search on a random packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "mechanics/model/ParticleSet.h"
#include "coupling/scene/RandomPlacement.h"
#include "mechanics/detection/TouchingPairs.h"

using namespace tmdem::mechanics;
using tmdem::coupling::place_random;
using Eigen::Vector3d;

namespace {

ParticleSet make_set(const std::vector<Vector3d>& x, const std::vector<double>& r) {
  ParticleSet set;
  for (std::size_t i = 0; i < x.size(); ++i) set.add(x[i], r[i], 1.0, 0);
  return set;
}

std::set<std::pair<std::int64_t, std::int64_t>> as_set(const std::vector<TouchingPair>& pairs) {
  std::set<std::pair<std::int64_t, std::int64_t>> s;
  for (const auto& p : pairs) s.insert({p.i, p.j});
  return s;
}

}  // namespace

TEST(TouchingPairs, RowOfTouchingSpheresAndWall) {
  // Three touching spheres along x (exact binary values), a fourth one far away, a floor
  // at y = 0 that sphere 0..2 touch and a wall at x = 10 that nobody touches.
  const auto set = make_set({{0.5, 0.5, 0}, {1.5, 0.5, 0}, {2.5, 0.5, 0}, {7.0, 3.0, 0}},
                            {0.5, 0.5, 0.5, 0.5});
  const std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0),
                                   Wall::through({10, 0, 0}, {-1, 0, 0}, 0)};
  const auto pairs = find_touching_pairs(set, walls);
  ASSERT_EQ(pairs.size(), 5u);
  EXPECT_EQ(pairs[0].i, 0); EXPECT_EQ(pairs[0].j, 1);
  EXPECT_EQ(pairs[1].i, 1); EXPECT_EQ(pairs[1].j, 2);
  EXPECT_EQ(pairs[2].i, 0); EXPECT_EQ(pairs[2].j, -1);
  EXPECT_EQ(pairs[3].i, 1); EXPECT_EQ(pairs[3].j, -1);
  EXPECT_EQ(pairs[4].i, 2); EXPECT_EQ(pairs[4].j, -1);
  for (const auto& p : pairs) EXPECT_EQ(p.gap_m, 0.0);
  EXPECT_EQ(wall_index(pairs[2].j), 0u);
}

TEST(TouchingPairs, GapThresholdIsRelativeToSmallerRadius) {
  // Radii 1 and 0.5; gap just under and just over 1e-9 * 0.5.
  const double r1 = 1.0, r2 = 0.5;
  const double below = 0.4e-9, above = 0.6e-9;
  auto set_below = make_set({{0, 0, 0}, {r1 + r2 + below, 0, 0}}, {r1, r2});
  auto set_above = make_set({{0, 0, 0}, {r1 + r2 + above, 0, 0}}, {r1, r2});
  EXPECT_EQ(find_touching_pairs(set_below, {}).size(), 1u);
  EXPECT_EQ(find_touching_pairs(set_above, {}).size(), 0u);
  // A larger fraction catches it; the gap is reported.
  const auto loose = find_touching_pairs(set_above, {}, 1e-6);
  ASSERT_EQ(loose.size(), 1u);
  EXPECT_NEAR(loose[0].gap_m, above, 1e-15);
  // Wall threshold uses r_i.
  auto near_wall = make_set({{0, 0.5 + 0.4e-9, 0}}, {0.5});
  auto far_wall = make_set({{0, 0.5 + 0.6e-9, 0}}, {0.5});
  const std::vector<Wall> floor = {Wall::through({0, 0, 0}, {0, 2, 0}, 0)};
  EXPECT_EQ(find_touching_pairs(near_wall, floor).size(), 1u);
  EXPECT_EQ(find_touching_pairs(far_wall, floor).size(), 0u);
}

TEST(TouchingPairs, OverlapsReportIds) {
  // 0-1 touch exactly (not an overlap), 2-3 overlap by 1e-3, 1-4 overlap by 1e-12 (below
  // 1e-9 of the radius: accepted as touching).
  const auto set = make_set({{0, 0, 0}, {2, 0, 0}, {10, 0, 0}, {11.999, 0, 0}, {2, 2 - 1e-12, 0}},
                            {1, 1, 1, 1, 1});
  const auto overlaps = find_overlaps(set);
  ASSERT_EQ(overlaps.size(), 1u);
  EXPECT_EQ(overlaps[0].i, 2);
  EXPECT_EQ(overlaps[0].j, 3);
  EXPECT_NEAR(overlaps[0].gap_m, -1e-3, 1e-12);
  EXPECT_TRUE(find_overlaps(make_set({{0, 0, 0}}, {1})).empty());
  EXPECT_TRUE(find_overlaps(ParticleSet{}).empty());
}

TEST(TouchingPairs, AgreesWithAllPairsOnRandomPacking) {
  // 2000 spheres of two sizes placed at random, then squeezed towards the centre so that
  // many pairs touch or overlap; compare with an O(N^2) search at several thresholds.
  const auto placed = place_random(2000, Vector3d(0, 0, 0), Vector3d(0.03, 0.03, 0.03),
                                   {0.001, 0.0006}, {0.5, 0.5}, 7, 3);
  ParticleSet set;
  for (std::size_t i = 0; i < placed.radii.size(); ++i) {
    set.add(0.9 * placed.positions[i], placed.radii[i], 1.0, 0);
  }
  const std::vector<Wall> walls = {Wall::through({0, 0.001, 0}, {0, 1, 0}, 0),
                                   Wall::through({0.02, 0, 0}, {-1, 0, 0}, 0)};
  for (double fraction : {1e-9, 0.05, 0.3}) {
    std::set<std::pair<std::int64_t, std::int64_t>> expected;
    for (std::size_t i = 0; i < set.size(); ++i) {
      for (std::size_t j = i + 1; j < set.size(); ++j) {
        const double gap = (set.position[i] - set.position[j]).norm() - set.radius[i] - set.radius[j];
        if (gap <= fraction * std::min(set.radius[i], set.radius[j])) expected.insert({i, j});
      }
      for (std::size_t w = 0; w < walls.size(); ++w) {
        if (walls[w].signed_distance(set.position[i]) - set.radius[i] <= fraction * set.radius[i]) {
          expected.insert({i, -1 - static_cast<std::int64_t>(w)});
        }
      }
    }
    const auto found = find_touching_pairs(set, walls, fraction);
    EXPECT_GT(expected.size(), 100u);
    EXPECT_EQ(found.size(), expected.size()) << "fraction " << fraction;
    EXPECT_EQ(as_set(found), expected) << "fraction " << fraction;
    for (const auto& p : found) {
      if (p.j >= 0) {
        EXPECT_LT(p.i, p.j);
      }
    }
  }
  // Overlaps: gap < -1e-9 min r.
  std::set<std::pair<std::int64_t, std::int64_t>> expected_overlaps;
  for (std::size_t i = 0; i < set.size(); ++i) {
    for (std::size_t j = i + 1; j < set.size(); ++j) {
      const double gap = (set.position[i] - set.position[j]).norm() - set.radius[i] - set.radius[j];
      if (gap < -1e-9 * std::min(set.radius[i], set.radius[j])) expected_overlaps.insert({i, j});
    }
  }
  EXPECT_GT(expected_overlaps.size(), 10u);
  EXPECT_EQ(as_set(find_overlaps(set)), expected_overlaps);
}
