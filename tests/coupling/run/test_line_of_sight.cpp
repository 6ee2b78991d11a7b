// Which near pairs see each other (coupling/bridge/LineOfSight.h): a pair is shadowed exactly
// when a third particle's centre lies closer to the segment between the pair's centres than
// its radius, between the two ends; contacts never are; across a periodic boundary the segment
// is the one through the nearest image.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "coupling/bridge/LineOfSight.h"

namespace tmdem::coupling {
namespace {

constexpr double kR = 1e-3;  // m

// The edges (i, j) of `pairs` over the particles of `set`, each a near pair (no contact).
thermal::ThermalNetwork near_pairs(const mechanics::ParticleSet& set,
                                   const std::vector<std::pair<int, int>>& pairs,
                                   const std::vector<bool>& contact = {}) {
  thermal::ThermalNetwork net;
  net.resize_nodes(set.size());
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    const bool touching = e < contact.size() && contact[e];
    net.add_edge(pairs[e].first, pairs[e].second, 0.0, 0.0, 0.0, touching);
  }
  return net;
}

TEST(LineOfSight, AThirdSphereOnTheCentreLineShadowsThePairAndOneBesideItDoesNot) {
  // 0 and 2 are 4.4 mm apart on the x axis; 1 sits between them, `offset` off the axis, with
  // radius 0.5 mm: it shadows the pair when the offset is below its radius.
  for (const double offset : {0.0, 0.4e-3, 0.6e-3}) {
    SCOPED_TRACE(offset);
    mechanics::ParticleSet set;
    set.add({0.0, 0.0, 0.0}, kR, 1.0, 0);
    set.add({2.2e-3, offset, 0.0}, 0.5e-3, 1.0, 0);
    set.add({4.4e-3, 0.0, 0.0}, kR, 1.0, 0);
    set.add({2.2e-3, 2.2e-3, 0.0}, kR, 1.0, 0);  // beside the line: never in the way
    const auto net = near_pairs(set, {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}});
    const auto shadowed = shadowed_edges(net, set);
    ASSERT_EQ(shadowed.size(), 5u);
    EXPECT_EQ(shadowed[2], offset < 0.5e-3 ? 1 : 0);
    for (const std::size_t e : {0u, 1u, 3u, 4u}) EXPECT_EQ(shadowed[e], 0) << e;
  }
  // A contact is never shadowed, whatever lies near it.
  mechanics::ParticleSet set;
  set.add({0.0, 0.0, 0.0}, kR, 1.0, 0);
  set.add({1.0e-3, 0.0, 0.0}, 0.2e-3, 1.0, 0);  // inside the overlap, on the line
  set.add({2.0e-3, 0.0, 0.0}, kR, 1.0, 0);
  const auto net = near_pairs(set, {{0, 2}, {0, 1}, {1, 2}}, {true, false, false});
  EXPECT_EQ(shadowed_edges(net, set)[0], 0);
}

TEST(LineOfSight, ASegmentRoundAPeriodicBoundaryIsTheNearestImage) {
  // x periodic over [0, 10 mm): a at 2 mm and b at 8 mm are 4 mm apart round the boundary,
  // where c (at 0) stands; d, at 5 mm, lies on the straight line inside the box, which is not
  // the pair's.
  for (const bool with_c : {true, false}) {
    SCOPED_TRACE(with_c);
    mechanics::ParticleSet set;
    set.box.periodic = {true, false, false};
    set.box.low = Eigen::Vector3d(0.0, 0.0, 0.0);
    set.box.high = Eigen::Vector3d(10e-3, 0.0, 0.0);
    set.add({2e-3, 0.0, 0.0}, kR, 1.0, 0);  // a
    set.add({8e-3, 0.0, 0.0}, kR, 1.0, 0);  // b
    set.add({5e-3, 0.0, 0.0}, kR, 1.0, 0);  // d
    std::vector<std::pair<int, int>> pairs{{0, 1}, {0, 2}, {1, 2}};
    if (with_c) {
      set.add({0.0, 0.0, 0.0}, kR, 1.0, 0);  // c
      pairs.insert(pairs.end(), {{0, 3}, {1, 3}});
    }
    const auto shadowed = shadowed_edges(near_pairs(set, pairs), set);
    EXPECT_EQ(shadowed[0], with_c ? 1 : 0);
    EXPECT_EQ(shadowed[1], 0);
    EXPECT_EQ(shadowed[2], 0);
  }
}

}  // namespace
}  // namespace tmdem::coupling
