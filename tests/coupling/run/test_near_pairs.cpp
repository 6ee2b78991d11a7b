// Near pairs of the gap modes: the network the frozen thermal problem builds holds exactly the
// pairs (and isothermal-wall pairs) within the reach, checked against a brute-force O(N^2) scan
// written here (the code itself searches a cell grid), with their gaps, and the contacts flagged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

// 120 random spheres (radii 0.6 and 1 mm, no mechanics) in a 12 mm cube, with gas across gaps
// up to `reach` x the smaller radius (surrounding_layer).
SceneBuilder random_gas_bed(double reach) {
  return thermal_scene()
      .set({{"effects.gas_conduction", true},
            {"fluid.model", "surrounding_layer"},
            {"fluid.cutoff", reach}})
      .add("generate", random_fill(120, "{ min = [0.0, 0.0, 0.0], max = [0.012, 0.012, 0.012] }",
                                   {{"radii", {0.0006, 0.001}}, {"fractions", {0.5, 0.5}}}));
}

// The scene's packing as a frozen thermal problem (its progress lines dropped).
FrozenThermalProblem frozen_problem(const Scene& scene) {
  std::ostringstream sink;
  ProgressReporter progress(sink, true, false);
  return build_frozen_thermal_problem(scene, progress);
}

using ExpectedGaps = std::map<std::pair<int, int>, double>;

// Every pair within reach x the smaller radius, with its gap, by brute force over all pairs;
// period > 0: x and z periodic with that period, each pair by its nearest image (`across`
// counts those round a boundary).
ExpectedGaps pairs_within(const std::vector<Particle>& P, double reach, double period = 0.0,
                          std::size_t* across = nullptr) {
  ExpectedGaps expected;
  for (std::size_t i = 0; i < P.size(); ++i)
    for (std::size_t j = i + 1; j < P.size(); ++j) {
      double d2 = 0.0;
      bool wrapped = false;
      for (int k = 0; k < 3; ++k) {
        double d = P[i].position_m[k] - P[j].position_m[k];
        if (period > 0.0 && k != 1 && std::abs(d) > period / 2) {
          d -= std::copysign(period, d);
          wrapped = true;
        }
        d2 += d * d;
      }
      const double gap = std::sqrt(d2) - P[i].radius_m - P[j].radius_m;
      if (gap <= reach * std::min(P[i].radius_m, P[j].radius_m)) {
        expected[{int(i), int(j)}] = gap;
        if (across) *across += wrapped;
      }
    }
  return expected;
}

// The network's particle edges are exactly `expected`, each with its gap; check(e, gap) on each.
template <class Check>
void expect_particle_edges(const thermal::ThermalNetwork& net, const ExpectedGaps& expected,
                           Check&& check) {
  ASSERT_EQ(net.edge_count(), expected.size());
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    const auto key = std::pair{std::min(net.edge_a[e], net.edge_b[e]), std::max(net.edge_a[e], net.edge_b[e])};
    const auto it = expected.find(key);
    ASSERT_NE(it, expected.end()) << key.first << "-" << key.second;
    EXPECT_NEAR(net.edge_gap_m[e], it->second, 1e-15);
    check(e, key, it->second);
  }
}

TEST(NearPairs, FrozenNetworkHoldsExactlyThePairsWithinTheReach) {
  // Random spheres (no mechanics) plus a touching lattice row; a hot floor and an adiabatic
  // side wall (no gas edges to it).
  const double reach = 0.4;
  const auto text = random_gas_bed(reach)
                        .add("generate", lattice({3, 2, 1}, {{"origin", {0.03, 0.001, 0.001}}}))
                        .add("wall", floor_wall({{"temperature", 350.0}}))
                        .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
                        .str();
  const auto scene = load_scene_text(text, "near");
  const auto problem = frozen_problem(scene);
  const auto& net = problem.system->network();

  // Brute force over every pair.
  const auto& P = scene.particles;
  const ExpectedGaps expected = pairs_within(P, reach);
  std::map<int, double> expected_wall;  // the floor only: the side wall is adiabatic
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double gap = P[i].position_m[1] - P[i].radius_m;
    if (gap <= reach * P[i].radius_m) expected_wall[int(i)] = gap;
  }
  ASSERT_GT(expected.size(), 20u);
  int touching = 0;
  for (const auto& [pair, gap] : expected) touching += gap <= 1e-15;
  ASSERT_GE(touching, 7);  // the lattice's
  ASSERT_GT(expected_wall.size(), 3u);

  expect_particle_edges(net, expected, [&](std::size_t e, const std::pair<int, int>& key, double gap) {
    // A pair is flagged a contact exactly when it touches (mechanics off: gap <= 1e-9 r).
    const double r_min = std::min(P[std::size_t(key.first)].radius_m, P[std::size_t(key.second)].radius_m);
    EXPECT_EQ(net.edge_in_contact[e] != 0, gap <= 1e-9 * r_min) << key.first << "-" << key.second << " gap " << gap;
  });
  ASSERT_EQ(net.wall_edge_count(), expected_wall.size());
  for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
    const auto it = expected_wall.find(net.wall_node[w]);
    ASSERT_NE(it, expected_wall.end());
    EXPECT_NEAR(net.wall_gap_m[w], it->second, 1e-15);
    EXPECT_EQ(net.wall_temperature_K[w], 350.0);
    EXPECT_EQ(net.wall_in_contact[w] != 0, it->second <= 1e-9 * P[std::size_t(net.wall_node[w])].radius_m);
  }
}

// The same with [periodic] along x and z (12 mm periods): the gas reaches round the boundaries,
// each gap that of the nearest image. A lattice row of 6 touching spheres closes a ring round x.
TEST(NearPairs, PeriodicNetworkHoldsThePairsRoundTheBoundariesWithTheirGaps) {
  const double reach = 0.4, L = 0.012;
  const auto text = random_gas_bed(reach)
                        .set({{"periodic.x", {0.0, L}}, {"periodic.z", {0.0, L}}})
                        .add("generate", lattice({6, 1, 1}, {{"origin", {0.001, 0.02, 0.001}}}))
                        .add("wall", floor_wall({{"temperature", 350.0}}))
                        .str();
  const auto scene = load_scene_text(text, "near");
  const auto problem = frozen_problem(scene);
  const auto& net = problem.system->network();

  const auto& P = scene.particles;
  std::size_t across = 0;
  const ExpectedGaps expected = pairs_within(P, reach, L, &across);
  ASSERT_GE(across, 2u);  // the ring's closing pair and a random pair round a boundary
  int touching = 0;
  for (const auto& [pair, gap] : expected) touching += gap <= 1e-15;
  ASSERT_GE(touching, 6);  // the ring's
  expect_particle_edges(net, expected, [](std::size_t, const std::pair<int, int>&, double) {});
}

}  // namespace
}  // namespace tmdem::coupling
