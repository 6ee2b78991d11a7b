// Detection across periodic boundaries: a pair across the boundary is found with the gap of its
// unwrapped image; the candidate table of a random packing in a periodic box is exactly the
// brute-force list by nearest images (also with periods of fewer than 3 cells); a period too
// short for the contact reach is refused.
#include <gtest/gtest.h>

#include <string>

#include <set>

#include "coupling/scene/RandomPlacement.h"
#include "mechanics/detection/ContactDetector.h"
#include "mechanics/detection/TouchingPairs.h"

using namespace tmdem::mechanics;
using tmdem::coupling::place_random;
using Eigen::Vector3d;

namespace {

PeriodicBox box_of(const Vector3d& low, const Vector3d& high, std::array<bool, 3> periodic) {
  PeriodicBox box;
  box.periodic = periodic;
  box.low = low;
  box.high = high;
  return box;
}

ParticleSet two_spheres(double x1, const PeriodicBox& box) {
  ParticleSet set;
  set.box = box;
  set.add(Vector3d(0.5e-3, 1e-3, 1e-3), 1e-3, 1.0, 0);
  set.add(Vector3d(x1, 1e-3, 1e-3), 1e-3, 1.0, 0);
  return set;
}

std::set<std::pair<int, int>> brute_force(const ParticleSet& set, double margin) {
  std::set<std::pair<int, int>> expected;
  for (std::size_t i = 0; i < set.size(); ++i)
    for (std::size_t j = i + 1; j < set.size(); ++j)
      if (set.branch(i, j).norm() - set.radius[i] - set.radius[j] <= margin)
        expected.insert({static_cast<int>(i), static_cast<int>(j)});
  return expected;
}

}  // namespace

TEST(PeriodicDetection, APairAcrossTheBoundaryHasTheGapOfItsUnwrappedImage) {
  // x periodic in [0, 10) mm: 0.5 mm and 8.4 mm are 2.1 mm apart round the boundary, a gap of
  // 0.1 mm between spheres of radius 1 mm, as for a sphere at -1.6 mm in open space.
  const PeriodicBox box = box_of(Vector3d(0, 0, 0), Vector3d(10e-3, 0, 0), {true, false, false});
  const ParticleSet across = two_spheres(8.4e-3, box);
  const ParticleSet image = two_spheres(-1.6e-3, PeriodicBox{});
  const auto found = find_touching_pairs(across, {}, 0.2);
  const auto expected = find_touching_pairs(image, {}, 0.2);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_EQ(expected.size(), 1u);
  EXPECT_EQ(found[0].i, 0);
  EXPECT_EQ(found[0].j, 1);
  EXPECT_NEAR(found[0].gap_m, 0.1e-3, 1e-15);
  EXPECT_NEAR(found[0].gap_m, expected[0].gap_m, 1e-15);
  // Without the period the two are 7.9 mm apart: no pair.
  EXPECT_TRUE(find_touching_pairs(two_spheres(8.4e-3, PeriodicBox{}), {}, 0.2).empty());

  ContactDetector detector(0.2e-3, 0.2e-3);
  ASSERT_TRUE(detector.update(across, {}, {}));
  ASSERT_EQ(detector.pairs().size(), 1u);
  EXPECT_EQ(detector.pairs()[0].i, 0);
  EXPECT_EQ(detector.pairs()[0].j, 1);
  // A move within half the margin keeps the table; a move across the boundary by 1.65 mm
  // (measured by the nearest image) rebuilds it, and the pair keeps its identity.
  ParticleSet moved = across;
  moved.position[1].x() = 8.45e-3;  // 0.05 mm: within half the margin, no rebuild
  EXPECT_FALSE(detector.update(moved, {}, {}));
  moved.position[1].x() = box.wrap(Vector3d(10.05e-3, 0, 0)).x();
  EXPECT_TRUE(detector.update(moved, {}, {}));
  ASSERT_EQ(detector.pairs().size(), 1u);
  EXPECT_EQ(detector.previous_index()[0], 0);  // the same pair: warm start kept
}

TEST(PeriodicDetection, WrappingAloneTriggersNoRebuild) {
  // A particle wrapped by one period has not moved: the displacement test goes through the
  // nearest image.
  const PeriodicBox box = box_of(Vector3d(0, 0, 0), Vector3d(10e-3, 0, 0), {true, false, false});
  ParticleSet set = two_spheres(9.99e-3, box);
  ContactDetector detector(0.2e-3, 0.2e-3);
  ASSERT_TRUE(detector.update(set, {}, {}));
  set.position[1].x() = box.wrap(Vector3d(10.01e-3, 0, 0)).x();  // 0.02 mm on, across
  EXPECT_NEAR(set.position[1].x(), 0.01e-3, 1e-15);
  EXPECT_FALSE(detector.update(set, {}, {}));
  EXPECT_EQ(detector.rebuild_count(), 1u);
}

TEST(PeriodicDetection, RandomPackingTableIsTheBruteForceListByNearestImages) {
  // Periods of 16 mm (x, z) and 16 or 4.6 mm along y (cells of 2.3 mm: 2 along y, fewer than
  // 3, so every cell along y is a neighbour of every other).
  for (const double period_y : {16e-3, 4.6e-3}) {
    const std::size_t count = period_y > 10e-3 ? 600 : 120;
    const auto placed = place_random(count, Vector3d(0, 0, 0), Vector3d(16e-3, period_y, 16e-3),
                                     {1e-3, 0.5e-3}, {0.5, 0.5}, 3, 3);
    ParticleSet set;
    set.box = box_of(Vector3d(-1e-3, -1e-3, -1e-3), Vector3d(15e-3, period_y - 1e-3, 15e-3),
                     {true, true, true});
    for (std::size_t i = 0; i < placed.positions.size(); ++i)
      set.add(set.box.wrap(placed.positions[i]), placed.radii[i], 1.0, 0);
    ContactDetector detector(0.3e-3, 0.3e-3);
    ASSERT_TRUE(detector.update(set, {}, {}));
    std::set<std::pair<int, int>> found;
    for (const auto& p : detector.pairs()) found.insert({p.i, p.j});
    EXPECT_EQ(found.size(), detector.pairs().size());  // no pair twice
    const auto expected = brute_force(set, detector.margin());
    EXPECT_GT(expected.size(), count / 2);
    EXPECT_EQ(found, expected) << "period_y " << period_y;
    // Some pairs are only pairs round a boundary.
    std::size_t across = 0;
    for (const auto& [i, j] : expected)
      across += (set.position[std::size_t(i)] - set.position[std::size_t(j)]).norm() >
                set.radius[std::size_t(i)] + set.radius[std::size_t(j)] + detector.margin();
    EXPECT_GT(across, 5u);
    // find_touching_pairs sees the same geometry (overlaps none: a random placement).
    const auto touching = find_touching_pairs(set, {}, 0.3);
    for (const auto& p : touching) {
      const double reach = 0.3 * std::min(set.radius[std::size_t(p.i)], set.radius[std::size_t(p.j)]);
      EXPECT_LE(p.gap_m, reach);
      EXPECT_NEAR(p.gap_m, set.branch(std::size_t(p.i), std::size_t(p.j)).norm() -
                               set.radius[std::size_t(p.i)] - set.radius[std::size_t(p.j)], 1e-18);
    }
  }
}

// A bed periodic in x and z moving fast along y (a piston landing on it): the periods hold only
// the motion across them to the fitted margin, so a look-ahead beyond it along y is taken (it
// was refused when every axis was held to it), and the table still lists every pair that can
// touch within the step. 6 mm periods, radii 0.5 and 1 mm: the fitted margin is 1 mm; each
// particle may move 1.5 mm, of which 0.2 mm across the periods.
TEST(PeriodicDetection, AFastMoveAlongTheWalledAxisIsHeldToTheListingMarginOnly) {
  const auto placed = place_random(100, Vector3d(0, 0, 0), Vector3d(6e-3, 40e-3, 6e-3), {1e-3, 0.5e-3},
                                   {0.5, 0.5}, 7, 3);
  ParticleSet set;
  set.box = box_of(Vector3d(0, 0, 0), Vector3d(6e-3, 0, 6e-3), {true, false, true});
  for (std::size_t i = 0; i < placed.positions.size(); ++i)
    set.add(set.box.wrap(placed.positions[i]), placed.radii[i], 1.0, 0);
  const std::vector<double> ahead(set.size(), 1.5e-3), across(set.size(), 0.2e-3);
  ContactDetector detector(0.1e-3, 10e-3);
  ASSERT_TRUE(detector.update(set, {}, ahead, {}, across));
  EXPECT_NEAR(detector.margin(), 6e-3, 1e-15);  // 4 x 1.5 mm, beyond the 1 mm that fits
  EXPECT_EQ(detector.pairs().size(), brute_force(set, detector.margin()).size());
  // Every particle moves within its look-aheads: up to 1.4 mm along y, 0.1 mm along x and z.
  // Neither test asks for a rebuild (1.41 + 1.5 < 3 mm; 0.15 + 0.2 < 0.5 mm), and every pair
  // in contact after the move is a candidate.
  std::uint32_t state = 12345;
  const auto uniform = [&state] {  // in [-1, 1)
    state = state * 1664525u + 1013904223u;
    return 2.0 * (state >> 8) / double(1u << 24) - 1.0;
  };
  for (std::size_t i = 0; i < set.size(); ++i)
    set.position[i] = set.box.wrap(set.position[i] + Vector3d(0.1e-3 * uniform(), 1.4e-3 * uniform(), 0.1e-3 * uniform()));
  EXPECT_FALSE(detector.update(set, {}, ahead, {}, across));
  std::set<std::pair<int, int>> listed;
  for (const auto& p : detector.pairs()) listed.insert({p.i, p.j});
  const auto touching = brute_force(set, 0.0);
  EXPECT_GT(touching.size(), 20u);
  for (const auto& pair : touching) EXPECT_TRUE(listed.count(pair)) << pair.first << " " << pair.second;
  // Across the periods the fitted margin holds for every pair: sphere 0 moved 0.85 mm along x
  // from where the table was built (within the listing margin: 0.85 + 1.5 < 3 mm) and another
  // sphere, both with their 0.2 mm look-aheads, may move apart by more than 1 mm: rebuilt.
  set.position[0] = set.box.wrap(detector.reference_positions()[0] + Vector3d(0.85e-3, 0, 0));
  EXPECT_TRUE(detector.update(set, {}, ahead, {}, across));
  // One sphere kicked sideways may take most of the fitted margin alone: 0.7 mm across with the
  // others at 0.2 mm (0.9 mm a pair at most) is taken; all at 0.6 mm (1.2 mm) is refused.
  std::vector<double> kicked = across;
  kicked[7] = 0.7e-3;
  ContactDetector one(0.1e-3, 10e-3);
  EXPECT_TRUE(one.update(set, {}, ahead, {}, kicked));
  ContactDetector fast(0.1e-3, 10e-3);
  EXPECT_THROW(fast.update(set, {}, ahead, {}, std::vector<double>(set.size(), 0.6e-3)), std::runtime_error);
}

TEST(PeriodicDetection, APeriodTooShortForTheReachIsRefused) {
  // Radius 1 mm: the reach is 2 mm + margin; a 3.9 mm period cannot hold twice that.
  const PeriodicBox box = box_of(Vector3d(0, 0, 0), Vector3d(3.9e-3, 0, 0), {true, false, false});
  ParticleSet set = two_spheres(2.6e-3, box);
  ContactDetector detector(0.1e-3, 2e-3);
  EXPECT_THROW(detector.update(set, {}, {}), std::runtime_error);
  // 4.6 mm: the margin (4 x the look-ahead of 0.1 mm) is 0.4 mm, but the pair is held to the
  // 0.3 mm that fits (half the period less a diameter) across the period: a move of 0.04 mm
  // plus both look-aheads stays within it, 0.11 mm does not and rebuilds. Look-aheads of 0.2
  // mm need 0.4 mm together: refused.
  set.box.high.x() = 4.6e-3;
  ContactDetector fitted(0.1e-3, 2e-3);
  const std::vector<double> ahead{0.1e-3, 0.1e-3};
  ASSERT_TRUE(fitted.update(set, {}, ahead));
  EXPECT_NEAR(fitted.margin(), 0.4e-3, 1e-15);
  EXPECT_EQ(fitted.pairs().size(), 1u);
  set.position[1].x() += 0.04e-3;
  EXPECT_FALSE(fitted.update(set, {}, ahead));
  set.position[1].x() += 0.07e-3;
  EXPECT_TRUE(fitted.update(set, {}, ahead));
  ContactDetector fast(0.1e-3, 2e-3);
  EXPECT_THROW(fast.update(set, {}, {0.2e-3, 0.2e-3}), std::runtime_error);
}

namespace {
std::string refusal(ParticleSet& set, double lookahead_m) {
  ContactDetector detector(0.1e-3, 2e-3);
  try {
    detector.update(set, {}, {lookahead_m, lookahead_m});
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "a look-ahead of " << lookahead_m << " m was accepted";
  return {};
}
}  // namespace

// The refusal's figures are the period's room and the look-ahead as they are, in significant
// digits; a look-ahead beyond the whole period (a particle crossing the box within a step) is
// blamed on the speed, not on the period.
TEST(PeriodicDetection, APeriodRefusalGivesItsFiguresAndBlamesARunawaySpeed) {
  // Room: half of 4.6 mm less a 2 mm diameter, 0.3 mm.
  const PeriodicBox box = box_of(Vector3d(0, 0, 0), Vector3d(4.6e-3, 0, 0), {true, false, false});
  ParticleSet set = two_spheres(2.6e-3, box);
  const std::string short_period = refusal(set, 0.2e-3);
  EXPECT_NE(short_period.find("leaves 0.0003 m"), std::string::npos) << short_period;
  EXPECT_NE(short_period.find("look-aheads along the periodic axes together, 0.0004 m"), std::string::npos)
      << short_period;
  EXPECT_NE(short_period.find("enlarge the period"), std::string::npos) << short_period;
  const std::string runaway = refusal(set, 9e7);
  EXPECT_NE(runaway.find("look-aheads along the periodic axes together, 1.8e+08 m"), std::string::npos) << runaway;
  EXPECT_NE(runaway.find("whole period 0.0046 m"), std::string::npos) << runaway;
  EXPECT_EQ(runaway.find("enlarge the period"), std::string::npos) << runaway;
}
