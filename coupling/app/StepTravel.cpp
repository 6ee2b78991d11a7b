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

// How far a sphere of radius r centred at x falls along the unit direction d before it meets
// the inside of the cylinder wall w (infinity: d along the axis, where the cylinder never stops
// it). Its centre stays within R - r of the axis: the positive root s of
// |x_perp + s d_perp|^2 = (R - r)^2, with the perpendicular parts to the axis. A sphere already at
// (or, by round-off, beyond) that distance rests: 0.
double fall_onto_cylinder(const Wall& w, const Vec3& x, double r, const Vec3& d) {
  Vec3 rel{}, x_perp{}, d_perp{};
  for (int k = 0; k < 3; ++k) rel[k] = x[k] - w.point_m[k];
  const double x_along = dot(rel, w.normal), d_along = dot(d, w.normal);
  for (int k = 0; k < 3; ++k) {
    x_perp[k] = rel[k] - x_along * w.normal[k];
    d_perp[k] = d[k] - d_along * w.normal[k];
  }
  const double a = dot(d_perp, d_perp);
  if (!(a > 1e-24)) return std::numeric_limits<double>::infinity();
  const double reach = w.radius_m - r;
  const double c = dot(x_perp, x_perp) - reach * reach;
  if (c >= 0.0) return 0.0;
  const double b = dot(x_perp, d_perp);
  return (-b + std::sqrt(b * b - a * c)) / a;  // c < 0: one positive root
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
    const Vec3 down{g[0] / g_norm, g[1] / g_norm, g[2] / g_norm};
    for (const auto& w : scene.walls) {
      if (w.cylinder) {
        // A cylinder across gravity (a drum, a horizontal pipe) is the floor of what lies in it
        // (before, only planes were: a drum 30 mm across was estimated at g x settle_time =
        // 49 m/s, and check asked for a time step 25 times shorter).
        fall = std::min(fall, fall_onto_cylinder(w, p.position_m, p.radius_m, down));
        continue;
      }
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
