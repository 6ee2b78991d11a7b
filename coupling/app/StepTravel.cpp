#include "coupling/app/StepTravel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tmdem::coupling {
namespace {

constexpr double kRestingOverlapFraction = 1e-9;  // of the radius: the loader's wall tolerance

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Largest speed a piston reaches within `t` seconds (0 when it is pushed out of the domain).
double piston_speed(const Scene& scene, const Wall& piston, double t) {
  const double a = piston.piston_force_N / piston.piston_mass_kg + dot(scene.gravity_m_per_s2, piston.normal);
  if (!(a > 0.0)) return 0.0;
  double distance = std::numeric_limits<double>::infinity();
  for (const auto& w : scene.walls) {
    if (&w == &piston || w.cylinder) continue;
    const double closing = -dot(w.normal, piston.normal);  // per metre the piston moves
    if (closing <= 0.0) continue;
    distance = std::min(distance, std::max(0.0, wall_signed_distance(w, piston.point_m)) / closing);
  }
  return std::min(a * t, std::sqrt(2.0 * a * distance));
}

}  // namespace

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
      const double up = -dot(w.normal, g) / g_norm;
      if (up <= 0.0) continue;
      // A particle resting on the floor may overlap it by round-off (a deposited bed: -4e-19 m),
      // as the loader allows (1e-9 of the radius, coupling/scene/SceneValidation.h): it rests,
      // not falls for the whole phase (the deposited periodic_pressed bed was estimated at
      // g x settle_time = 49 m/s, and check warned that the run would stop).
      const double distance = wall_signed_distance(w, p.position_m) - p.radius_m;
      if (distance >= -kRestingOverlapFraction * p.radius_m)
        fall = std::min(fall, std::max(distance, 0.0) / up);
    }
    height = std::max(height, fall);
  }
  if (!std::isfinite(r_min)) return out;
  out.smallest_radius_m = r_min;
  const bool dynamic = scene.effects.mechanics == MechanicsMode::Dynamic;
  out.fraction = dynamic ? kDynamicTravelFraction : kSettleTravelFraction;
  const double t = dynamic ? scene.duration_s : scene.mechanics.settle_time_s;
  out.speed_m_per_s = std::min(g_norm * t, std::sqrt(2.0 * g_norm * height));
  for (const auto& w : scene.walls)
    if (w.piston && !w.cylinder && w.piston_mass_kg > 0.0)
      out.speed_m_per_s = std::max(out.speed_m_per_s, piston_speed(scene, w, t));
  out.travel_m = out.speed_m_per_s * scene.mechanics.time_step_s;
  return out;
}

}  // namespace tmdem::coupling
