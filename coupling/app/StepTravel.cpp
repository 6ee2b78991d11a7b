#include "coupling/app/StepTravel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "coupling/bridge/SceneToMechanics.h"
#include "mechanics/detection/TouchingPairs.h"

namespace tmdem::coupling {
namespace {

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

// Per particle, whether it rests at the start on something below it that rests too: a wall
// whose surface faces up where it touches (Wall::normal_at, plane or cylinder), a fixed
// particle, or a resting particle whose centre lies lower along gravity, touching within the
// loader's 1e-9 of the radius (`touching`: find_touching_pairs of the scene's particles and
// walls). A bed laid by deposition or imported rests throughout; a particle held only from the
// side (between walls) or on something that falls does not. Taken lowest first, so that a
// particle's supports are settled before it.
std::vector<std::uint8_t> resting_at_start(const Scene& scene, const std::vector<mechanics::TouchingPair>& touching,
                                           const Vec3& down) {
  const std::size_t n = scene.particles.size();
  const std::vector<mechanics::Wall> walls = make_mechanics_walls(scene);
  const Eigen::Vector3d up(-down[0], -down[1], -down[2]);
  // Per particle, the touching partners that lie below it (particle ids, or a wall's code).
  std::vector<std::vector<std::int64_t>> below(n);
  for (const auto& t : touching) {
    const auto& pi = scene.particles[std::size_t(t.i)];
    if (mechanics::is_wall(t.j)) {
      const Eigen::Vector3d x(pi.position_m[0], pi.position_m[1], pi.position_m[2]);
      if (walls[mechanics::wall_index(t.j)].normal_at(x).dot(up) > 0.0) below[std::size_t(t.i)].push_back(t.j);
      continue;
    }
    const auto& pj = scene.particles[std::size_t(t.j)];
    Vec3 d{};
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      d[k] = pj.position_m[k] - pi.position_m[k];
      d2 += d[k] * d[k];
    }
    // Pairs touching across a period (their plain distance is not their contact's) hold nothing.
    if (std::sqrt(d2) > 1.001 * (pi.radius_m + pj.radius_m)) continue;
    const double dj = dot(d, down);  // > 0: j lies below i
    if (dj > 0.0) below[std::size_t(t.i)].push_back(t.j);
    if (dj < 0.0) below[std::size_t(t.j)].push_back(t.i);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> depth(n);  // along gravity: larger is lower
  for (std::size_t i = 0; i < n; ++i) depth[i] = dot(scene.particles[i].position_m, down);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] > depth[b]; });
  std::vector<std::uint8_t> resting(n, 0);
  for (const std::size_t i : order) {
    if (scene.particles[i].fixed) {
      resting[i] = 1;
      continue;
    }
    for (const std::int64_t j : below[i])
      if (mechanics::is_wall(j) || resting[std::size_t(j)] != 0) {
        resting[i] = 1;
        break;
      }
  }
  return resting;
}

}  // namespace

StepTravel estimate_step_travel(const Scene& scene) {
  if (scene.effects.mechanics == MechanicsMode::Off) return StepTravel{};
  // Geometry only: the masses (and so the materials) play no part.
  mechanics::ParticleSet set;
  set.box = periodic_box(scene.periodic);
  set.reserve(scene.particles.size());
  for (const auto& p : scene.particles)
    set.add(Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]), p.radius_m, 1.0, 0, p.fixed);
  return estimate_step_travel(
      scene, mechanics::find_touching_pairs(set, make_mechanics_walls(scene), kRestingOverlapFraction));
}

StepTravel estimate_step_travel(const Scene& scene, const std::vector<mechanics::TouchingPair>& touching) {
  StepTravel out;
  if (scene.effects.mechanics == MechanicsMode::Off) return out;
  const Vec3& g = scene.gravity_m_per_s2;
  const double g_norm = std::hypot(g[0], g[1], g[2]);
  double r_min = std::numeric_limits<double>::infinity();
  double height = 0.0;  // largest fall onto a floor, m; infinity: some particle has no floor
  const Vec3 down = g_norm > 0.0 ? Vec3{g[0] / g_norm, g[1] / g_norm, g[2] / g_norm} : Vec3{};
  // A particle resting on what rests (a laid or imported bed) does not fall: before, every
  // particle of a laid bed was taken to fall onto the floor from where it lies, and the deposited
  // 100-layer column_2d, at rest from its first step, was estimated at 3.96 r_min a step and
  // warned about.
  const std::vector<std::uint8_t> resting =
      g_norm > 0.0 ? resting_at_start(scene, touching, down) : std::vector<std::uint8_t>(scene.particles.size(), 0);
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const auto& p = scene.particles[i];
    if (p.fixed) continue;
    r_min = std::min(r_min, p.radius_m);
    if (resting[i] != 0) ++out.resting_particles;
    if (g_norm == 0.0 || resting[i] != 0) continue;
    double fall = std::numeric_limits<double>::infinity();
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
      // A particle touching this floor, even overlapping it by round-off (a deposited bed:
      // -4e-19 m, as the loader allows), is resting and never gets here: the distance is positive
      // (before, the deposited periodic_pressed bed was estimated at g x settle_time = 49 m/s,
      // and check warned that the run would stop).
      fall = std::min(fall, (wall_signed_distance(w, p.position_m) - p.radius_m) / up);
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
