#pragma once
// The benchmark pile: nx * nx * layers touching spheres (R = 1 mm, steel) on a simple cubic
// lattice of spacing 2R resting on y = 0, at rest from the first step (no settling run).
// top_mass_factor: the top layer's spheres are this many times heavier (a loaded bed).

#include <cmath>
#include <cstdint>

#include "mechanics/model/ParticleSet.h"

namespace tmdem::bench {

constexpr double kRadius = 1e-3;  // m

inline mechanics::ParticleSet lattice(int nx, int layers, double spacing_factor = 1.0,
                                      double top_mass_factor = 1.0) {
  mechanics::ParticleSet set;
  const double m = mechanics::sphere_mass(kRadius, 7800.0);
  const double d = 2.0 * kRadius * spacing_factor;
  set.reserve(static_cast<std::size_t>(nx) * nx * layers);
  for (int y = 0; y < layers; ++y) {
    for (int z = 0; z < nx; ++z) {
      for (int x = 0; x < nx; ++x) {
        set.add(Eigen::Vector3d(kRadius + x * d, kRadius + y * d, kRadius + z * d), kRadius,
                y == layers - 1 ? top_mass_factor * m : m, 0);
      }
    }
  }
  return set;
}

inline int width_for(std::int64_t count, int layers) {
  return static_cast<int>(std::lround(std::sqrt(static_cast<double>(count) / layers)));
}

}  // namespace tmdem::bench
