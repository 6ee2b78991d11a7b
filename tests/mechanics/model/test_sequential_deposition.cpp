// Sequential deposition against closed-form pockets and the packing fraction the literature
// gives for it.
#include <gtest/gtest.h>

#include <algorithm>
#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <stdexcept>

#include "mechanics/model/SequentialDeposition.h"

namespace tmdem::mechanics {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double r = 1e-3;  // m

// Three touching spheres of radius r on the floor y = 0 (gravity -y), centred on the origin in
// x-z, in a box large enough not to matter.
SequentialDeposition triangle_on_floor(std::vector<Vec3>& centres) {
  SequentialDeposition box(Vec3(-0.01, 0.0, -0.01), Vec3(0.01, 0.02, 0.01), 1, -1, r);
  const double circumradius = 2.0 * r / std::sqrt(3.0);
  for (int k = 0; k < 3; ++k) {
    const double angle = 2.0 * M_PI * k / 3.0;
    centres.emplace_back(circumradius * std::cos(angle), r, circumradius * std::sin(angle));
    box.add_sphere(centres.back(), r);
  }
  return box;
}

TEST(SequentialDeposition, DroppedAboveThePocketRestsAtTheTetrahedronApex) {
  std::vector<Vec3> c;
  SequentialDeposition box = triangle_on_floor(c);
  std::mt19937_64 rng(1);
  const auto d = box.drop(r, Vec3::Zero(), rng);
  ASSERT_TRUE(d.resting);
  // Regular tetrahedron of edge 2r: apex 2r sqrt(2/3) above the base centres.
  EXPECT_NEAR(d.position.y(), r + 2.0 * r * std::sqrt(2.0 / 3.0), 1e-15);
  EXPECT_NEAR(d.position.x(), 0.0, 1e-15);
  EXPECT_NEAR(d.position.z(), 0.0, 1e-15);
  for (const auto& x : c) EXPECT_NEAR((d.position - x).norm(), 2.0 * r, 1e-15);
}

TEST(SequentialDeposition, LandingOnOneSphereRollsIntoThePocket) {
  // Dropped between the centre of sphere 0 and the pocket, off every symmetry line: it lands on
  // sphere 0, rolls on it, meets a second, rolls on both, and stops on the third.
  for (const Vec3& start : {Vec3(0.6 * 2.0 * r / std::sqrt(3.0), 0.0, 0.1 * r),
                           Vec3(0.3 * r, 0.0, -0.05 * r), Vec3(0.4 * r, 0.0, 0.3 * r)}) {
    std::vector<Vec3> c;
    SequentialDeposition box = triangle_on_floor(c);
    std::mt19937_64 rng(1);
    const auto d = box.drop(r, start, rng);
    ASSERT_TRUE(d.resting);
    EXPECT_GE(d.moves, 3u) << "it should have rolled";
    EXPECT_NEAR(d.position.y(), r + 2.0 * r * std::sqrt(2.0 / 3.0), 1e-14);
    EXPECT_NEAR(d.position.x(), 0.0, 1e-14);
    EXPECT_NEAR(d.position.z(), 0.0, 1e-14);
  }
}

TEST(SequentialDeposition, DroppedOnTheOuterSideRollsOffToTheFloor) {
  std::vector<Vec3> c;
  SequentialDeposition box = triangle_on_floor(c);
  std::mt19937_64 rng(1);
  // Above sphere 0, a little outside its centre (away from the others), off the x axis.
  const Vec3 start = c[0] + Vec3(0.3 * r, 0.0, 0.1 * r);
  const auto d = box.drop(r, start, rng);
  ASSERT_TRUE(d.resting);
  // Rolled over sphere 0 down to its equator, then the floor: it touches both, in the vertical
  // plane through sphere 0's centre and the drop point.
  EXPECT_NEAR(d.position.y(), r, 1e-15);
  EXPECT_NEAR((d.position - c[0]).norm(), 2.0 * r, 1e-15);
  const Vec3 direction = (d.position - c[0]) / (2.0 * r);
  EXPECT_NEAR(direction.x(), 0.3 / std::hypot(0.3, 0.1), 1e-12);
  EXPECT_NEAR(direction.z(), 0.1 / std::hypot(0.3, 0.1), 1e-12);
}

TEST(SequentialDeposition, InASlotOneDiameterWideThreeDisksStackAsInThePlane) {
  // z-extent exactly 2r: the walls keep the spheres in one plane, as disks. Two on the floor
  // touching, the third on top of both: 2r sin(60 deg) above them.
  SequentialDeposition slot(Vec3(-0.01, 0.0, -r), Vec3(0.01, 0.02, r), 1, -1, r);
  slot.add_sphere(Vec3(-r, r, 0.0), r);
  slot.add_sphere(Vec3(r, r, 0.0), r);
  std::mt19937_64 rng(3);
  const auto d = slot.drop(r, Vec3(0.2 * r, 0.0, 0.0), rng);
  ASSERT_TRUE(d.resting);
  EXPECT_NEAR(d.position.x(), 0.0, 1e-15);
  EXPECT_NEAR(d.position.y(), r + std::sqrt(3.0) * r, 1e-15);
  EXPECT_NEAR(d.position.z(), 0.0, 1e-15);
}

TEST(SequentialDeposition, SphereOnTopRollsOffInADrawnDirection) {
  // A sphere dropped exactly above a lone sphere on the floor rolls off it to the floor.
  SequentialDeposition box(Vec3(-0.01, 0.0, -0.01), Vec3(0.01, 0.02, 0.01), 1, -1, r);
  box.add_sphere(Vec3(0.0, r, 0.0), r);
  std::mt19937_64 rng(5);
  const auto d = box.drop(r, Vec3::Zero(), rng);
  ASSERT_TRUE(d.resting);
  EXPECT_NEAR(d.position.y(), r, 1e-15);
  EXPECT_NEAR(std::hypot(d.position.x(), d.position.z()), 2.0 * r, 1e-15);
}

// Pairs closer than their contact distance (relative), and spheres out of the box.
struct Overlaps {
  double worst_overlap = 0.0;  // relative to the contact distance
  int outside = 0;
  int untouching = 0;  // spheres touching nothing (no contact within 1e-9 relative, no face)
};
Overlaps check(const DepositionResult& d, const std::vector<double>& radii, const Vec3& lo,
               const Vec3& hi) {
  Overlaps o;
  const std::size_t n = radii.size();
  for (std::size_t i = 0; i < n; ++i) {
    bool touches = false;
    for (int a = 0; a < 3; ++a) {
      const double below = d.positions[i][a] - radii[i] - lo[a];
      const double above = hi[a] - d.positions[i][a] - radii[i];
      if (below < -1e-12 || (a != 1 && above < -1e-12)) ++o.outside;
      if (std::abs(below) < 1e-12 || (a != 1 && std::abs(above) < 1e-12)) touches = true;
    }
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const double contact = radii[i] + radii[j];
      const double gap = ((d.positions[i] - d.positions[j]).norm() - contact) / contact;
      if (j > i) o.worst_overlap = std::max(o.worst_overlap, -gap);
      if (std::abs(gap) < 1e-9) touches = true;
    }
    if (!touches) ++o.untouching;
  }
  return o;
}

// Spheres whose weight their contacts cannot carry: gravity (up, here +y) must lie in the cone
// of the contact normals (sphere-sphere, and the box's floor and side faces) of each sphere, the
// frictionless equilibrium each one was left in (spheres laid later only add contacts). Checked
// over every single, pair and triple of contacts: up = sum lambda_k n_k with lambda_k >= 0.
int unbalanced(const DepositionResult& d, const std::vector<double>& radii, const Vec3& lo,
               const Vec3& hi, int dimension) {
  int count = 0;
  const Vec3 up(0.0, 1.0, 0.0);
  for (std::size_t i = 0; i < radii.size(); ++i) {
    std::vector<Vec3> n;
    const Vec3& x = d.positions[i];
    if (std::abs(x.y() - radii[i] - lo.y()) < 1e-12) n.push_back(up);
    for (int a = 0; a < dimension; ++a) {
      if (a == 1) continue;
      if (std::abs(x[a] - radii[i] - lo[a]) < 1e-12) n.push_back(Vec3::Unit(a));
      if (std::abs(hi[a] - x[a] - radii[i]) < 1e-12) n.push_back(-Vec3::Unit(a));
    }
    for (std::size_t j = 0; j < radii.size(); ++j) {
      const Vec3 b = x - d.positions[j];
      if (j != i && std::abs(b.norm() - radii[i] - radii[j]) < 1e-9 * radii[i])
        n.push_back(b.normalized());
    }
    bool held = false;
    const std::size_t k = n.size();
    auto balances = [&](std::initializer_list<std::size_t> ids) {
      Eigen::MatrixXd N(3, static_cast<Eigen::Index>(ids.size()));
      Eigen::Index c = 0;
      for (const auto id : ids) N.col(c++) = n[id];
      const Eigen::VectorXd lambda = N.colPivHouseholderQr().solve(up);
      return (N * lambda - up).norm() < 1e-9 && lambda.minCoeff() >= -1e-9;
    };
    for (std::size_t a = 0; a < k && !held; ++a) {
      held = balances({a});
      for (std::size_t b = a + 1; b < k && !held; ++b) {
        held = balances({a, b});
        for (std::size_t c = b + 1; c < k && !held; ++c) held = balances({a, b, c});
      }
    }
    if (!held) ++count;
  }
  return count;
}

TEST(SequentialDeposition, TwoSizedBedHasNoOverlapAndEverySphereRests) {
  std::vector<double> radii;
  for (int k = 0; k < 300; ++k) radii.push_back(k < 150 ? 0.5e-3 : 1e-3);
  const Vec3 lo(0.0, 0.0, 0.0), hi(0.01, 0.02, 0.01);
  const DepositionResult d = deposit_spheres(radii, lo, hi, 1, -1, 11);
  EXPECT_EQ(d.stopped_short, 0u);
  const Overlaps o = check(d, radii, lo, hi);
  EXPECT_LT(o.worst_overlap, 1e-12);
  EXPECT_EQ(o.outside, 0);
  EXPECT_EQ(o.untouching, 0);
  EXPECT_EQ(unbalanced(d, radii, lo, hi, 3), 0);
  // Reproducible to the bit.
  const DepositionResult again = deposit_spheres(radii, lo, hi, 1, -1, 11);
  for (std::size_t i = 0; i < radii.size(); ++i) EXPECT_EQ(d.positions[i], again.positions[i]);
  // Obstacles are built upon, never overlapped.
  std::vector<double> more(60, 0.8e-3);
  const DepositionResult on_top = deposit_spheres(more, lo, hi, 1, -1, 12, 3, d.positions, radii);
  for (std::size_t i = 0; i < more.size(); ++i)
    for (std::size_t j = 0; j < radii.size(); ++j)
      EXPECT_GE((on_top.positions[i] - d.positions[j]).norm(), (more[i] + radii[j]) * (1 - 1e-12));
}

TEST(SequentialDeposition, InTwoDimensionsDisksStayInThePlaneAndRest) {
  std::vector<double> radii;
  for (int k = 0; k < 200; ++k) radii.push_back(k % 3 == 0 ? 1e-3 : 0.6e-3);
  const Vec3 lo(0.0, 0.0, -1.0), hi(0.02, 0.04, 1.0);  // z range: only its middle counts
  const DepositionResult d = deposit_spheres(radii, lo, hi, 1, -1, 5, 2);
  EXPECT_EQ(d.stopped_short, 0u);
  for (const auto& x : d.positions) EXPECT_EQ(x.z(), 0.0);
  const Overlaps o = check(d, radii, Vec3(0.0, 0.0, -1e9), Vec3(0.02, 0.04, 1e9));
  EXPECT_LT(o.worst_overlap, 1e-12);
  EXPECT_EQ(o.outside, 0);
  EXPECT_EQ(o.untouching, 0);
  EXPECT_EQ(unbalanced(d, radii, lo, hi, 2), 0);
}

TEST(SequentialDeposition, EqualSpheresPackAtTheVisscherBolsterliFraction) {
  // Visscher & Bolsterli (1972) and later sequential-deposition studies give a bulk solid
  // fraction near 0.58 for equal spheres (0.5815; Jullien & Meakin's deposition, 0.58). Measured
  // here in a core away from the walls, the floor and the top.
  const int n = 5000;
  std::vector<double> radii(n, 0.5e-3);
  const double side = 0.016;  // m: 16 diameters
  const Vec3 lo(0.0, 0.0, 0.0), hi(side, 0.05, side);
  const DepositionResult d = deposit_spheres(radii, lo, hi, 1, -1, 7);
  EXPECT_EQ(d.stopped_short, 0u);
  const double margin = 2.5e-3;  // m: five diameters from the sides, the floor and the top
  const double y_lo = margin, y_hi = d.top_m - margin;
  ASSERT_GT(y_hi - y_lo, 0.008);
  // Solid fraction of the core by sampling points with a fixed generator (standard error 0.001).
  std::vector<double> y(n);
  std::vector<int> by_height(n);
  for (int i = 0; i < n; ++i) by_height[i] = i;
  std::sort(by_height.begin(), by_height.end(),
            [&](int a, int b) { return d.positions[a].y() < d.positions[b].y(); });
  for (int i = 0; i < n; ++i) y[i] = d.positions[by_height[i]].y();
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> ux(margin, side - margin), uy(y_lo, y_hi);
  const int samples = 200000;
  int inside = 0;
  for (int s = 0; s < samples; ++s) {
    const Vec3 x(ux(rng), uy(rng), ux(rng));
    const auto first = std::lower_bound(y.begin(), y.end(), x.y() - 0.5e-3) - y.begin();
    for (auto k = first; k < n && y[k] < x.y() + 0.5e-3; ++k)
      if ((d.positions[by_height[k]] - x).squaredNorm() < 0.25e-6) {
        ++inside;
        break;
      }
  }
  const double fraction = static_cast<double>(inside) / samples;
  EXPECT_NEAR(fraction, 0.58, 0.015);
  RecordProperty("solid_fraction", std::to_string(fraction));
}

TEST(SequentialDeposition, PeriodicSidesSupportAcrossTheBoundary) {
  // Periodic in x and z: no side faces; every sphere wrapped into the box, no overlap and every
  // weight carried by the contact normals, all by the nearest image; and spheres near a side
  // rest on spheres across it (some contacts cross the boundary).
  const int n = 600;
  std::vector<double> radii(n, 0.5e-3);
  const double side = 0.008;  // m: 8 diameters
  const Vec3 lo(0.0, 0.0, 0.0), hi(side, 0.03, side);
  const DepositionResult d = deposit_spheres(radii, lo, hi, 1, -1, 3, 3, {}, {}, {true, false, true});
  EXPECT_EQ(d.stopped_short, 0u);
  const auto nearest = [&](Vec3 b) {
    for (const int a : {0, 2}) b[a] -= side * std::round(b[a] / side);
    return b;
  };
  int crossing = 0, unbalanced_count = 0;
  double worst_overlap = 0.0;
  const Vec3 up(0.0, 1.0, 0.0);
  for (int i = 0; i < n; ++i) {
    const Vec3& x = d.positions[i];
    EXPECT_TRUE(x.x() >= 0.0 && x.x() < side && x.z() >= 0.0 && x.z() < side) << i;
    std::vector<Vec3> normals;
    if (std::abs(x.y() - 0.5e-3) < 1e-12) normals.push_back(up);
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      const Vec3 direct = x - d.positions[j];
      const Vec3 b = nearest(direct);
      const double gap = (b.norm() - 1e-3) / 1e-3;
      worst_overlap = std::max(worst_overlap, -gap);
      if (std::abs(gap) < 1e-9) {
        normals.push_back(b.normalized());
        if ((b - direct).norm() > 0.5 * side && j > i) ++crossing;
      }
    }
    bool held = false;
    for (std::size_t a = 0; a < normals.size() && !held; ++a)
      for (std::size_t b = a; b < normals.size() && !held; ++b)
        for (std::size_t c = b; c < normals.size() && !held; ++c) {
          Eigen::Matrix3d N;
          N << normals[a], normals[b], normals[c];
          const Eigen::Vector3d lambda = N.colPivHouseholderQr().solve(up);
          held = (N * lambda - up).norm() < 1e-9 && lambda.minCoeff() >= -1e-9;
        }
    if (!held) ++unbalanced_count;
  }
  EXPECT_LT(worst_overlap, 1e-12);
  EXPECT_EQ(unbalanced_count, 0);
  EXPECT_GT(crossing, 20);
}

TEST(SequentialDeposition, BadArgumentsAndALowBoxAreReported) {
  const Vec3 lo(0.0, 0.0, 0.0), hi(0.004, 0.004, 0.004);
  EXPECT_THROW(deposit_spheres({1e-3}, lo, hi, 3, -1, 1), std::invalid_argument);
  EXPECT_THROW(deposit_spheres({1e-3}, lo, hi, 1, 0, 1), std::invalid_argument);
  EXPECT_THROW(deposit_spheres({1e-3}, lo, hi, 2, -1, 1, 2), std::invalid_argument);  // 2D: along z
  EXPECT_THROW(deposit_spheres({-1e-3}, lo, hi, 1, -1, 1), std::invalid_argument);
  EXPECT_THROW(deposit_spheres({3e-3}, lo, hi, 1, -1, 1), std::invalid_argument);  // too narrow
  try {
    deposit_spheres(std::vector<double>(40, 1e-3), lo, hi, 1, -1, 1);
    FAIL() << "40 spheres of 2 mm cannot lie in a 4 mm cube";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("too low"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tmdem::mechanics
