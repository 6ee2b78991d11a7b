#pragma once
// Small scenes shared by the mechanics tests.

#include <numbers>
#include <vector>

#include "mechanics/NscdIntegrator.h"
#include "mechanics/RandomPlacement.h"

namespace tmdem::mechanics::test {

inline constexpr double kG = 9.81;        // m/s^2
inline constexpr double kRadius = 1e-3;   // m
inline constexpr double kDensity = 7800;  // kg/m^3

inline Material steel(double friction) { return Material{kDensity, 2.1e11, 0.3, friction}; }

// A box of walls: floor y = 0, sides x = 0 and x = width, and (3D) z = 0 and z = depth.
inline std::vector<Wall> box_walls(double width, double depth, int dimension) {
  std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0),
                             Wall::through({0, 0, 0}, {1, 0, 0}, 0),
                             Wall::through({width, 0, 0}, {-1, 0, 0}, 0)};
  if (dimension == 3) {
    walls.push_back(Wall::through({0, 0, 0}, {0, 0, 1}, 0));
    walls.push_back(Wall::through({0, 0, depth}, {0, 0, -1}, 0));
  }
  return walls;
}

// `count` spheres dropped at random in a box of walls (two radii), ready to settle.
inline NscdIntegrator random_pile(std::size_t count, int dimension, double friction,
                                  std::uint64_t seed, NscdParameters parameters = {}) {
  // Wide, shallow boxes: a few layers once settled (Gauss-Seidel cost grows with depth).
  const double width = dimension == 3 ? 0.016 : 0.06;
  const double height = dimension == 3 ? 0.012 : 0.02;
  const Eigen::Vector3d lo(0, 0, dimension == 3 ? 0.0 : 0.0);
  const Eigen::Vector3d hi(width, height, dimension == 3 ? width : 0.0);
  const auto placed = place_random(count, lo, hi, {kRadius, 0.7 * kRadius}, {0.5, 0.5}, seed,
                                   dimension);
  ParticleSet set;
  for (std::size_t i = 0; i < count; ++i) {
    set.add(placed.positions[i], placed.radii[i], sphere_mass(placed.radii[i], kDensity), 0);
  }
  return NscdIntegrator(std::move(set), {steel(friction)}, box_walls(width, width, dimension),
                        Eigen::Vector3d(0, -kG, 0), dimension, parameters);
}

}  // namespace tmdem::mechanics::test
