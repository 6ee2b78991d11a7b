// Cylinder walls (mechanics/model/Wall.h): geometry, a sphere resting in a horizontal cylinder, and a
// sphere dropped inside one.
#include <gtest/gtest.h>

#include <cmath>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

constexpr double kCylinderRadius = 5e-3;  // m

Wall horizontal_cylinder() { return Wall::cylinder({0, 0, 0}, {0, 0, 2.0}, kCylinderRadius, 0); }

NscdIntegrator sphere_in(const Vector3d& position, const Wall& wall) {
  ParticleSet set;
  set.add(position, kRadius, sphere_mass(kRadius, kDensity), 0);
  return NscdIntegrator(std::move(set), {steel(0.3)}, {wall}, Vector3d(0, -kG, 0), 3, {});
}

}  // namespace

TEST(CylinderWall, DistanceAndNormalAreRadial) {
  const Wall w = Wall::cylinder({1, 2, 3}, {0, 0, 5}, 0.5, 0);
  EXPECT_EQ(w.normal, Vector3d(0, 0, 1));
  // 0.3 from the axis in x, anywhere along it: 0.2 inside, normal pointing back to the axis.
  EXPECT_NEAR(w.signed_distance({1.3, 2, -7}), 0.2, 1e-15);
  EXPECT_TRUE(w.normal_at({1.3, 2, -7}).isApprox(Vector3d(-1, 0, 0), 1e-15));
  EXPECT_NEAR(w.signed_distance({1, 2 + 0.8, 3}), -0.3, 1e-15);  // outside: negative
  EXPECT_TRUE(w.normal_at({1, 2.8, 3}).isApprox(Vector3d(0, -1, 0), 1e-15));
  // On the axis: some unit radial direction.
  const Vector3d n = w.normal_at({1, 2, 9});
  EXPECT_NEAR(n.norm(), 1.0, 1e-15);
  EXPECT_NEAR(n.dot(w.normal), 0.0, 1e-15);
  EXPECT_THROW(Wall::cylinder({0, 0, 0}, {0, 0, 1}, 0.0, 0), std::invalid_argument);
}

// At the bottom of a horizontal cylinder the wall carries the sphere's weight along +y.
TEST(CylinderWall, SphereRestingAtTheBottomCarriesItsWeight) {
  auto sim = sphere_in(Vector3d(0, -(kCylinderRadius - kRadius), 0), horizontal_cylinder());
  const double weight = sphere_mass(kRadius, kDensity) * kG;
  for (int step = 0; step < 2000; ++step) {
    ASSERT_TRUE(sim.step().converged);
    ASSERT_EQ(sim.contacts().size(), 1u) << "step " << step;
    ASSERT_NEAR(sim.contacts()[0].normal_force_N, weight, 1e-6 * weight) << "step " << step;
  }
  const auto& c = sim.contacts()[0];
  EXPECT_EQ(c.j, -1);
  EXPECT_TRUE(c.normal.isApprox(Vector3d(0, 1, 0), 1e-12));
  EXPECT_LT(c.tangential_force_N.norm(), 1e-9 * weight);
  EXPECT_NEAR(sim.particles().position[0].y(), -(kCylinderRadius - kRadius), 1e-9 * kRadius);
}

// Dropped from the axis, the sphere falls R - r and stops at the bottom without passing the
// curved wall: the contact is found on the way, not after a penetration.
TEST(CylinderWall, DroppedSphereStopsAtTheBottom) {
  auto sim = sphere_in(Vector3d(0, 0, 0), horizontal_cylinder());
  for (int step = 0; step < 1000; ++step) sim.step();
  const Vector3d x = sim.particles().position[0];
  EXPECT_NEAR(x.y(), -(kCylinderRadius - kRadius), 1e-6 * kRadius);
  EXPECT_NEAR(x.x(), 0.0, 1e-12);
  EXPECT_LT(sim.stats().max_penetration_m, 1e-3 * kRadius);
  EXPECT_LT(sim.max_speed(), 1e-6);
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_NEAR(sim.contacts()[0].normal_force_N, sphere_mass(kRadius, kDensity) * kG,
              1e-6 * sphere_mass(kRadius, kDensity) * kG);
}
