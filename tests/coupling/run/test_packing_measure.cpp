// PackingMeasure.h against closed forms: a simple cubic lattice of n^3 touching spheres fills its
// bounding box to pi/6 whatever n and r (porosity 1 - pi/6), its height 2 n r along gravity; a
// tilted gravity projects the box's extents; no measure in 2D, without gravity, with a cylinder
// wall.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupling/run/PackingMeasure.h"
#include "mechanics/model/ParticleSet.h"

using namespace tmdem::coupling;
namespace mechanics = tmdem::mechanics;

namespace {

mechanics::ParticleSet cubic_lattice(int n, double r) {
  mechanics::ParticleSet set;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        set.add(Eigen::Vector3d((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r), r, 1.0, 0);
  return set;
}

}  // namespace

TEST(PackingMeasure, SimpleCubicLatticeFillsPiOverSixOfItsBox) {
  Scene scene;
  scene.gravity_m_per_s2 = {0.0, 0.0, -9.81};
  for (const int n : {1, 3, 6}) {
    const double r = 1e-3 * n;
    const auto measure = measure_packing(scene, cubic_lattice(n, r));
    ASSERT_TRUE(measure.has_value());
    EXPECT_NEAR(measure->porosity, 1.0 - std::numbers::pi / 6.0, 1e-12);
    EXPECT_NEAR(measure->bed_height_m, 2 * n * r, 1e-15);
  }
  // Gravity along (0, 3, -4)/5: the box's width along it, 0.6 of the y extent (4 mm) plus 0.8 of
  // the z extent (4 mm).
  scene.gravity_m_per_s2 = {0.0, 3.0, -4.0};
  EXPECT_NEAR(measure_packing(scene, cubic_lattice(2, 1e-3))->bed_height_m, 5.6e-3, 1e-15);
}

TEST(PackingMeasure, NoneWhereTheBoxIsNotTheBed) {
  Scene scene;
  const auto lattice = cubic_lattice(2, 1e-3);
  EXPECT_FALSE(measure_packing(scene, lattice).has_value());  // no gravity
  scene.gravity_m_per_s2 = {0.0, 0.0, -9.81};
  scene.dimension = 2;
  EXPECT_FALSE(measure_packing(scene, lattice).has_value());
  scene.dimension = 3;
  scene.walls.push_back(Wall{});
  scene.walls.back().cylinder = true;
  EXPECT_FALSE(measure_packing(scene, lattice).has_value());
}
