#pragma once
// Spherical particles stored as a structure of arrays: the hot loops (detection, contact
// solver, position update) each touch only the arrays they need.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/model/PeriodicBox.h"

namespace tmdem::mechanics {

// Mass of a solid sphere, kg. Particles are spheres in 2D runs too (motion is planar, the
// bodies are not discs).
double sphere_mass(double radius_m, double density_kg_per_m3);

struct ParticleSet {
  std::vector<Eigen::Vector3d> position;          // m, centre
  std::vector<Eigen::Vector3d> velocity;          // m/s
  std::vector<Eigen::Vector3d> angular_velocity;  // rad/s
  std::vector<double> radius;                     // m
  std::vector<double> mass;                       // kg
  std::vector<double> inertia;                    // kg m^2, 2/5 m r^2 (solid sphere)
  std::vector<int> material;                      // index into the material list
  // 1 = does not move (treated as infinite mass and inertia). uint8 rather than
  // std::vector<bool> so that elements are addressable and reads are plain loads.
  std::vector<std::uint8_t> fixed;
  // The space the particles live in: periodic along none, some or all axes. Held here rather
  // than passed beside the set because every pair vector of the set needs it (detection, the
  // contact problem, touching pairs, the coupling's gaps): a set carries its own geometry.
  PeriodicBox box;

  // x_i - x_j through the nearest periodic image (plain x_i - x_j without periodic axes), m.
  Eigen::Vector3d branch(std::size_t i, std::size_t j) const {
    return box.minimum_image(position[i] - position[j]);
  }

  std::size_t size() const { return radius.size(); }
  bool empty() const { return radius.empty(); }
  void reserve(std::size_t count);

  // Appends one particle at rest; returns its id. Inertia is set to 2/5 m r^2.
  std::size_t add(const Eigen::Vector3d& position_m, double radius_m, double mass_kg,
                  int material_index, bool is_fixed = false);

  // Throws std::invalid_argument if the arrays differ in length or hold a non-finite value,
  // a non-positive radius or mass.
  void validate() const;

  double max_radius() const;  // m, 0 when empty
  double min_radius() const;  // m, 0 when empty
};

}  // namespace tmdem::mechanics
