#include "coupling/app/StepTravel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tmdem::coupling {

StepTravel estimate_step_travel(const Scene& scene) {
  StepTravel out;
  if (scene.effects.mechanics == MechanicsMode::Off) return out;
  const Vec3& g = scene.gravity_m_per_s2;
  const double g_norm = std::hypot(g[0], g[1], g[2]);
  double r_min = std::numeric_limits<double>::infinity();
  double height = 0.0;  // largest fall onto a floor, m; infinity: some particle has no floor
  for (const auto& p : scene.particles) {
    if (p.fixed) continue;
    r_min = std::min(r_min, p.radius_m);
    if (g_norm == 0.0) continue;
    double fall = std::numeric_limits<double>::infinity();
    for (const auto& w : scene.walls) {
      if (w.cylinder) continue;
      // cos of the angle between the wall's normal and "up" (-g / |g|).
      const double up = -(w.normal[0] * g[0] + w.normal[1] * g[1] + w.normal[2] * g[2]) / g_norm;
      if (up <= 0.0) continue;
      const double distance = wall_signed_distance(w, p.position_m) - p.radius_m;
      if (distance >= 0.0) fall = std::min(fall, distance / up);
    }
    height = std::max(height, fall);
  }
  if (!std::isfinite(r_min)) return out;
  out.smallest_radius_m = r_min;
  const double t = scene.effects.mechanics == MechanicsMode::Settle ? scene.mechanics.settle_time_s
                                                                    : scene.duration_s;
  out.speed_m_per_s = std::min(g_norm * t, std::sqrt(2.0 * g_norm * height));
  out.travel_m = out.speed_m_per_s * scene.mechanics.time_step_s;
  return out;
}

}  // namespace tmdem::coupling
