#include "coupling/run/PackingMeasure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace tmdem::coupling {

std::optional<PackingMeasure> measure_packing(const Scene& scene, const mechanics::ParticleSet& particles) {
  if (scene.dimension != 3 || particles.empty() || particles.box.any()) return std::nullopt;
  const Vec3& g = scene.gravity_m_per_s2;
  if (g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0) return std::nullopt;
  for (const auto& wall : scene.walls)
    if (wall.cylinder) return std::nullopt;
  double low[3], high[3];
  std::fill(low, low + 3, std::numeric_limits<double>::infinity());
  std::fill(high, high + 3, -std::numeric_limits<double>::infinity());
  double solid_m3 = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double r = particles.radius[i];
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], particles.position[i][a] - r);
      high[a] = std::max(high[a], particles.position[i][a] + r);
    }
    solid_m3 += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  // Height along gravity: the box's extent along the unit vector of g (its axes' extents
  // projected; exact when gravity is along an axis, as for every deposit).
  const double norm = std::hypot(g[0], g[1], g[2]);
  double height = 0.0, volume = 1.0;
  for (int a = 0; a < 3; ++a) {
    height += std::abs(g[a] / norm) * (high[a] - low[a]);
    volume *= high[a] - low[a];
  }
  return PackingMeasure{height, 1.0 - solid_m3 / volume};
}

}  // namespace tmdem::coupling
