// Candidate table: complete within the margin, rebuilt only when needed, warm-start map.
#include <gtest/gtest.h>
#include <omp.h>

#include <set>

#include "mechanics/detection/ContactDetector.h"
#include "coupling/scene/RandomPlacement.h"

using namespace tmdem::mechanics;
using tmdem::coupling::place_random;
using Eigen::Vector3d;

namespace {

ParticleSet random_set(std::size_t count, std::uint64_t seed) {
  const auto placed = place_random(count, Vector3d(0, 0, 0), Vector3d(0.02, 0.02, 0.02),
                                   {0.001, 0.0005}, {0.5, 0.5}, seed, 3);
  ParticleSet set;
  for (std::size_t i = 0; i < count; ++i) set.add(placed.positions[i], placed.radii[i], 1.0, 0);
  return set;
}

std::set<std::pair<int, int>> brute_force(const ParticleSet& set, const std::vector<Wall>& walls,
                                          double margin) {
  std::set<std::pair<int, int>> expected;
  for (std::size_t i = 0; i < set.size(); ++i) {
    for (std::size_t j = i + 1; j < set.size(); ++j) {
      if ((set.position[i] - set.position[j]).norm() - set.radius[i] - set.radius[j] <= margin) {
        expected.insert({static_cast<int>(i), static_cast<int>(j)});
      }
    }
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (walls[w].signed_distance(set.position[i]) - set.radius[i] <= margin) {
        expected.insert({static_cast<int>(i), -1 - static_cast<int>(w)});
      }
    }
  }
  return expected;
}

}  // namespace

TEST(ContactDetector, ListsExactlyThePairsWithinTheMargin) {
  ParticleSet set = random_set(800, 1);
  const std::vector<Wall> walls = {Wall::through({0, 0.002, 0}, {0, 1, 0}, 0)};
  ContactDetector detector(4e-4, 4e-4);
  ASSERT_TRUE(detector.update(set, walls, {}));
  EXPECT_EQ(detector.margin(), 4e-4);
  std::set<std::pair<int, int>> found;
  for (const auto& p : detector.pairs()) found.insert({p.i, p.j});
  EXPECT_EQ(found.size(), detector.pairs().size());  // no duplicates
  const auto expected = brute_force(set, walls, 4e-4);
  EXPECT_GT(expected.size(), 200u);
  EXPECT_EQ(found, expected);
  // Sorted by (i, j).
  for (std::size_t k = 1; k < detector.pairs().size(); ++k) {
    const auto& a = detector.pairs()[k - 1];
    const auto& b = detector.pairs()[k];
    EXPECT_TRUE(a.i < b.i || (a.i == b.i && a.j < b.j));
  }
}

TEST(ContactDetector, RebuildsOnlyPastHalfTheMargin) {
  ParticleSet set = random_set(200, 2);
  ContactDetector detector(1e-4, 1e-4);
  EXPECT_TRUE(detector.update(set, {}, {}));
  EXPECT_EQ(detector.rebuild_count(), 1u);
  set.position[7].x() += 0.49e-4;  // below half the margin
  EXPECT_FALSE(detector.update(set, {}, {}));
  // The look-ahead counts: 0.49e-4 moved + 0.02e-4 ahead > 0.5e-4.
  std::vector<double> ahead(set.size(), 0.0);
  ahead[7] = 0.02e-4;
  EXPECT_TRUE(detector.update(set, {}, ahead));
  EXPECT_EQ(detector.rebuild_count(), 2u);
  // Displacements are measured from the last rebuild.
  set.position[7].x() += 0.49e-4;
  EXPECT_FALSE(detector.update(set, {}, {}));
  detector.invalidate();
  EXPECT_TRUE(detector.update(set, {}, {}));
}

TEST(ContactDetector, MapsPairsToThePreviousTable) {
  ParticleSet set;
  set.add(Vector3d(0, 0, 0), 1.0, 1.0, 0);
  set.add(Vector3d(2.05, 0, 0), 1.0, 1.0, 0);
  set.add(Vector3d(10, 0, 0), 1.0, 1.0, 0);
  ContactDetector detector(0.1, 0.1);
  detector.update(set, {}, {});
  ASSERT_EQ(detector.pairs().size(), 1u);
  // Particle 2 comes close to 1: the old pair keeps its index, the new one is marked new.
  set.position[2] = Vector3d(4.1, 0, 0);
  ASSERT_TRUE(detector.update(set, {}, {}));
  ASSERT_EQ(detector.pairs().size(), 2u);
  EXPECT_EQ(detector.pairs()[0].i, 0);
  EXPECT_EQ(detector.pairs()[0].j, 1);
  EXPECT_EQ(detector.previous_index()[0], 0);
  EXPECT_EQ(detector.pairs()[1].i, 1);
  EXPECT_EQ(detector.pairs()[1].j, 2);
  EXPECT_EQ(detector.previous_index()[1], -1);
}

TEST(ContactDetector, SkipsPairsOfFixedParticles) {
  ParticleSet set;
  set.add(Vector3d(0, 0, 0), 1.0, 1.0, 0, true);
  set.add(Vector3d(2, 0, 0), 1.0, 1.0, 0, true);
  set.add(Vector3d(4, 0, 0), 1.0, 1.0, 0, false);
  const std::vector<Wall> walls = {Wall::through({0, -1, 0}, {0, 1, 0}, 0)};
  ContactDetector detector(0.1, 0.1);
  detector.update(set, walls, {});
  // (0,1) both fixed: skipped. (1,2) kept. Walls: only the moving particle.
  ASSERT_EQ(detector.pairs().size(), 2u);
  EXPECT_EQ(detector.pairs()[0].i, 1);
  EXPECT_EQ(detector.pairs()[0].j, 2);
  EXPECT_EQ(detector.pairs()[1].i, 2);
  EXPECT_EQ(detector.pairs()[1].j, -1);
}

// A table put back with restore() decides like the detector it was saved from: no rebuild below
// half the margin from the saved reference positions, a rebuild past it that maps the saved
// pairs to the new table; unsorted pairs are refused, empty references mean "rebuild".
TEST(ContactDetector, RestoredTableDecidesLikeTheSavedOne) {
  ParticleSet set = random_set(200, 2);
  ContactDetector saved(1e-4, 1e-4);
  saved.update(set, {}, {});
  ContactDetector restored(1e-4, 1e-4);
  restored.restore(saved.margin(), saved.rebuild_count(), saved.reference_positions(), saved.pairs());
  set.position[7].x() += 0.49e-4;
  EXPECT_FALSE(restored.update(set, {}, {}));
  set.position[7].x() += 0.02e-4;
  EXPECT_TRUE(saved.update(set, {}, {}));
  EXPECT_TRUE(restored.update(set, {}, {}));
  EXPECT_EQ(restored.rebuild_count(), 2u);
  ASSERT_EQ(restored.pairs().size(), saved.pairs().size());
  for (std::size_t k = 0; k < saved.pairs().size(); ++k) {
    EXPECT_EQ(restored.pairs()[k].i, saved.pairs()[k].i);
    EXPECT_EQ(restored.pairs()[k].j, saved.pairs()[k].j);
    EXPECT_EQ(restored.previous_index()[k], saved.previous_index()[k]);
  }

  ContactDetector cold(1e-4, 1e-4);
  cold.restore(1e-4, 0, {}, {});
  EXPECT_TRUE(cold.update(set, {}, {}));
  EXPECT_THROW(cold.restore(1e-4, 1, saved.reference_positions(), {{1, 2}, {0, 1}}),
               std::invalid_argument);
}

// Parallel rebuilds (parallel_from = 0: threads at any size) list the same table, in the same
// order, with the same warm-start map, for 1 and 2 threads, and it is the brute-force one.
TEST(ContactDetector, OneAndTwoThreadsListTheSameTable) {
  ParticleSet set = random_set(500, 3);
  set.fixed[0] = set.fixed[1] = 1;
  const std::vector<Wall> walls = {Wall::through({0, 0.002, 0}, {0, 1, 0}, 0),
                                   Wall::through({0.018, 0, 0}, {-1, 0, 0}, 0)};
  const int threads_before = omp_get_max_threads();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    ParticleSet moved = set;
    ContactDetector detector(3e-4, 3e-4, 0);
    detector.update(moved, walls, {});
    for (std::size_t i = 0; i < moved.size(); i += 3) moved.position[i].y() -= 2e-4;
    EXPECT_TRUE(detector.update(moved, walls, {}));
    return detector;
  };
  const ContactDetector one = run(1), two = run(2);
  omp_set_num_threads(threads_before);
  ASSERT_EQ(one.pairs().size(), two.pairs().size());
  ASSERT_GT(one.pairs().size(), 200u);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < one.pairs().size(); ++k) {
    EXPECT_EQ(one.pairs()[k].i, two.pairs()[k].i) << k;
    EXPECT_EQ(one.pairs()[k].j, two.pairs()[k].j) << k;
    EXPECT_EQ(one.previous_index()[k], two.previous_index()[k]) << k;
    kept += one.previous_index()[k] >= 0 ? 1 : 0;
  }
  EXPECT_GT(kept, one.pairs().size() / 2);
  // The table itself: exactly the pairs within the margin (none of two fixed particles).
  ParticleSet moved = set;
  for (std::size_t i = 0; i < moved.size(); i += 3) moved.position[i].y() -= 2e-4;
  auto expected = brute_force(moved, walls, 3e-4);
  expected.erase({0, 1});
  for (std::size_t w = 0; w < walls.size(); ++w) {
    expected.erase({0, -1 - static_cast<int>(w)});
    expected.erase({1, -1 - static_cast<int>(w)});
  }
  std::set<std::pair<int, int>> found;
  for (std::size_t k = 0; k < two.pairs().size(); ++k) {
    found.insert({two.pairs()[k].i, two.pairs()[k].j});
    if (k > 0) {
      const auto& a = two.pairs()[k - 1];
      const auto& b = two.pairs()[k];
      EXPECT_TRUE(a.i < b.i || (a.i == b.i && a.j < b.j)) << k;
    }
  }
  EXPECT_EQ(found, expected);
}

// A moving wall (a piston) has a margin of its own: falling fast far above the bed it lists its
// own pairs within its reach but leaves the particles' table to their own look-aheads (a piston
// at 7 m/s had made every pair of 1,000 spheres a candidate while it fell). Once it can touch a
// particle within the coming step it may hand its speed to the bed, and the particles' pairs are
// listed within its reach too.
TEST(ContactDetector, AFallingPistonWidensItsOwnPairsUntilItCanTouchTheBed) {
  ParticleSet set = random_set(800, 3);
  const std::vector<double> still(set.size(), 1e-6);  // m: the particles' look-aheads
  const double piston_ahead = 4e-3;                      // m: the piston's
  auto table = [&](double piston_height) {
    std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0),
                               Wall::through({0, piston_height, 0}, {0, -1, 0}, 0)};
    walls[1].make_piston(0.01, 4.0);
    ContactDetector detector(4e-4, 4e-4);
    EXPECT_TRUE(detector.update(set, walls, still, {0.0, piston_ahead}));
    std::set<std::pair<int, int>> found;
    for (const auto& p : detector.pairs()) found.insert({p.i, p.j});
    return std::tuple{found, detector.margin(), detector.wall_margin(), walls};
  };
  // 10 mm above the bed's top (0.02 m): out of reach within the step.
  const auto [far, far_margin, far_wall_margin, far_walls] = table(0.03 + 0.001);
  EXPECT_EQ(far_margin, 4e-4);
  EXPECT_EQ(far_wall_margin, 2.0 * piston_ahead);  // 4 x the look-ahead, clamped, never below 2 x
  std::set<std::pair<int, int>> expected = brute_force(set, {far_walls[0]}, 4e-4);
  for (std::size_t i = 0; i < set.size(); ++i)
    if (far_walls[1].signed_distance(set.position[i]) - set.radius[i] <= 2.0 * piston_ahead)
      expected.insert({static_cast<int>(i), -2});
  EXPECT_EQ(far, expected);
  // 3 mm above the top: within its look-ahead, every pair within its reach is listed.
  const auto [near, near_margin, near_wall_margin, near_walls] = table(0.02 + 0.003);
  EXPECT_EQ(near_margin, 2.0 * piston_ahead);
  EXPECT_EQ(near, brute_force(set, near_walls, 2.0 * piston_ahead));
  EXPECT_GT(near.size(), 3 * far.size());
}

// Once a landed piston has stopped, the table its landing widened is rebuilt to the look-aheads
// of the moment: no particle moves far under a piston at rest, so the displacement test would
// never ask, and every step after the landing kept every pair within the landing's reach
// (periodic_pressed: 500,500 candidates, 35-50 s a step). A table the particles' own speed
// widened is left to the displacement test, as before.
TEST(ContactDetector, ATableALandingPistonWidenedShrinksOnceThePistonHasStopped) {
  ParticleSet set = random_set(800, 3);
  const std::vector<double> still(set.size(), 1e-6);  // m
  std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0),
                             Wall::through({0, 0.02 + 0.003, 0}, {0, -1, 0}, 0)};
  walls[1].make_piston(0.01, 4.0);
  ContactDetector detector(4e-4, 4e-4);
  ASSERT_TRUE(detector.update(set, walls, still, {0.0, 4e-3}));  // landing: within reach
  ASSERT_EQ(detector.margin(), 8e-3);
  EXPECT_TRUE(detector.widened_by_wall());
  const std::size_t landing_pairs = detector.pairs().size();
  // A checkpoint taken now restores the decision too.
  ContactDetector restored(4e-4, 4e-4);
  restored.restore(detector.margin(), detector.rebuild_count(), detector.reference_positions(), detector.pairs(),
                   detector.reference_wall_points(), detector.wall_margin(), detector.widened_by_wall());
  // The piston has stopped (nothing has moved): rebuilt to the particles' margin.
  for (ContactDetector* d : {&detector, &restored}) {
    ASSERT_TRUE(d->update(set, walls, still, {0.0, 1e-6}));
    EXPECT_EQ(d->margin(), 4e-4);
    std::set<std::pair<int, int>> found;
    for (const auto& p : d->pairs()) found.insert({p.i, p.j});
    EXPECT_EQ(found, brute_force(set, walls, 4e-4));
    EXPECT_LT(3 * found.size(), landing_pairs);
    EXPECT_FALSE(d->update(set, walls, still, {0.0, 1e-6}));  // and stays so
  }
  // Without a piston, a table the particles' speed widened (look-aheads of 2 mm, then at rest)
  // is kept until the displacements ask.
  ContactDetector own(4e-4, 4e-4);
  ASSERT_TRUE(own.update(set, {walls[0]}, std::vector<double>(set.size(), 2e-3)));
  EXPECT_FALSE(own.widened_by_wall());
  EXPECT_FALSE(own.update(set, {walls[0]}, still));
  EXPECT_EQ(own.margin(), 4e-3);
}

// A wall that can touch the bed within the step may hand its speed to particles at rest, whose
// own look-aheads are nil: while it is engaged, each particle is held to the displacement test
// with at least the wall's look-ahead. A landing taken in parts (NscdIntegrator::step) kicks
// spheres across a table listed a few parts before.
TEST(ContactDetector, WhileAWallCanTouchTheBedEveryParticleIsHeldToItsReach) {
  ParticleSet set = random_set(800, 3);
  double top = 0.0;
  std::size_t lowest = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    top = std::max(top, set.position[i].y() + set.radius[i]);
    if (set.position[i].y() < set.position[lowest].y()) lowest = i;
  }
  const std::vector<Wall> walls = [&] {
    std::vector<Wall> w = {Wall::through({0, 0, 0}, {0, 1, 0}, 0),
                           Wall::through({0, top + 1.2e-3, 0}, {0, -1, 0}, 0)};  // 1.2 mm above the bed
    w[1].make_piston(0.01, 4.0);
    return w;
  }();
  const std::vector<double> still(set.size(), 1e-6);  // m
  // A table the particles' own look-aheads (2 mm) widened to a 4 mm margin.
  auto table = [&] {
    ContactDetector detector(4e-4, 4e-4);
    EXPECT_TRUE(detector.update(set, walls, std::vector<double>(set.size(), 2e-3), {0.0, 1e-3}));
    EXPECT_EQ(detector.margin(), 4e-3);
    EXPECT_FALSE(detector.widened_by_wall());
    return detector;
  };
  // The lowest sphere moved 1 mm: with its own 1 um within half the margin, with a piston's
  // 1.5 mm not; and 2 x 1.5 mm is within the margin, so only the hold on each particle asks.
  ParticleSet moved = set;
  moved.position[lowest].y() -= 1e-3;
  ContactDetector engaged = table();
  ASSERT_TRUE(engaged.wall_engaged(moved, walls[1], 1.5e-3, still));
  EXPECT_TRUE(engaged.update(moved, walls, still, {0.0, 1.5e-3}));
  // A piston that cannot reach the bed within the step (look-ahead 1 mm, gap 1.2 mm) hands
  // nothing on: the displacement is within the margin.
  ContactDetector out_of_reach = table();
  ASSERT_FALSE(out_of_reach.wall_engaged(moved, walls[1], 1e-3, still));
  EXPECT_FALSE(out_of_reach.update(moved, walls, still, {0.0, 1e-3}));
  // A reach beyond half the widest margin (max_margin 4e-4 here) is one a table cannot hold.
  EXPECT_TRUE(out_of_reach.wall_reach_exceeds_margin(2.1e-4));
  EXPECT_FALSE(out_of_reach.wall_reach_exceeds_margin(1.9e-4));
}
