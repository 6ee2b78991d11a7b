#pragma once
// Small scenes shared by the mechanics tests.

#include <algorithm>
#include <numbers>
#include <vector>

#include "mechanics/integrator/NscdIntegrator.h"
#include "coupling/scene/RandomPlacement.h"

namespace tmdem::mechanics::test {

// Random packings come from the scene generator's placement (coupling/scene; compiled into
// the mechanics test program, tests/CMakeLists.txt).
using tmdem::coupling::place_random;

// The fixtures here were written and measured with Gauss-Seidel ("nlgs") at tolerance 1e-6,
// no tolerance schedule and a stop test relative to the whole impulses, while the library's
// defaults are others, so they name theirs.
inline NscdParameters nlgs_parameters() {
  NscdParameters parameters;
  parameters.solver = "nlgs";
  parameters.tolerance = 1e-6;
  parameters.fall_tolerance = 0.0;
  parameters.stop_travel_fraction = 0.0;
  parameters.retry_parts = 1;  // measured before unconverged steps were retaken in parts
  return parameters;
}

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

// `count` spheres dropped at random in a box of walls (two radii), ready to settle; `scale`
// widens and heightens the box for more spheres.
inline NscdIntegrator random_pile(std::size_t count, int dimension, double friction,
                                  std::uint64_t seed, NscdParameters parameters = nlgs_parameters(),
                                  double rolling_friction = 0.0, double scale = 1.0) {
  // Wide, shallow boxes: a few layers once settled (Gauss-Seidel cost grows with depth).
  const double width = (dimension == 3 ? 0.016 : 0.06) * scale;
  const double height = (dimension == 3 ? 0.012 : 0.02) * scale;
  const Eigen::Vector3d lo(0, 0, dimension == 3 ? 0.0 : 0.0);
  const Eigen::Vector3d hi(width, height, dimension == 3 ? width : 0.0);
  const auto placed = place_random(count, lo, hi, {kRadius, 0.7 * kRadius}, {0.5, 0.5}, seed,
                                   dimension);
  ParticleSet set;
  for (std::size_t i = 0; i < count; ++i) {
    set.add(placed.positions[i], placed.radii[i], sphere_mass(placed.radii[i], kDensity), 0);
  }
  Material material = steel(friction);
  material.rolling_friction = rolling_friction;
  return NscdIntegrator(std::move(set), {material}, box_walls(width, width, dimension),
                        Eigen::Vector3d(0, -kG, 0), dimension, parameters);
}

// 40 disks (radii 1 and 0.7 mm) dropped at random into a 2D box 8 mm wide (about six
// layers), mu = 0.5 between disks and on the floor, side walls frictionless (material 1),
// solver tolerance 1e-8, stepped until every speed is below 1e-9 m/s (at most 5,000 steps; the
// caller checks max_speed()). See test_nscd_rest.cpp for why 1e-8. full_sweep_every: the
// solver's active-set sweeps (ActiveContactSet.h; 1: every sweep visits every candidate).
inline NscdIntegrator settled_disk_pile(std::uint64_t seed = 1,
                                        int full_sweep_every = nlgs_parameters().full_sweep_every) {
  constexpr double width = 0.008, height = 0.03;
  const auto placed = place_random(40, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(width, height, 0),
                                   {kRadius, 0.7 * kRadius}, {0.5, 0.5}, seed, 2);
  ParticleSet set;
  for (std::size_t i = 0; i < placed.positions.size(); ++i)
    set.add(placed.positions[i], placed.radii[i], sphere_mass(placed.radii[i], kDensity), 0);
  auto walls = box_walls(width, width, 2);
  for (std::size_t w = 1; w < walls.size(); ++w) walls[w].material = 1;
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-8;
  parameters.full_sweep_every = full_sweep_every;
  // The pile the solver tests were measured on (with active-set corrections the pile settles
  // elsewhere, and its problem is one on which "nlgs" cold stalls at 1.5e-6 before 1e-8).
  parameters.correction_full_sweep_every = 1;
  NscdIntegrator sim(std::move(set), {steel(0.5), steel(0.0)}, walls, Eigen::Vector3d(0, -kG, 0), 2,
                     parameters);
  for (int step = 0; step < 5000 && !(step > 10 && sim.max_speed() < 1e-9); ++step) sim.step();
  return sim;
}

// Steps `steps` times; the largest speed seen and the largest distance any particle moved
// from where it was at the start (the rest tests).
struct Drift {
  double fastest_m_per_s = 0.0;
  double moved_m = 0.0;
};
inline Drift drift_over(NscdIntegrator& sim, int steps) {
  const auto start = sim.particles().position;
  Drift d;
  for (int step = 0; step < steps; ++step) {
    sim.step();
    d.fastest_m_per_s = std::max(d.fastest_m_per_s, sim.max_speed());
    for (std::size_t i = 0; i < start.size(); ++i)
      d.moved_m = std::max(d.moved_m, (sim.particles().position[i] - start[i]).norm());
  }
  return d;
}

}  // namespace tmdem::mechanics::test
