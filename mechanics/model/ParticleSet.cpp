#include "mechanics/model/ParticleSet.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tmdem::mechanics {

double sphere_mass(double radius_m, double density_kg_per_m3) {
  return 4.0 / 3.0 * std::numbers::pi * radius_m * radius_m * radius_m * density_kg_per_m3;
}

void ParticleSet::reserve(std::size_t count) {
  position.reserve(count);
  velocity.reserve(count);
  angular_velocity.reserve(count);
  radius.reserve(count);
  mass.reserve(count);
  inertia.reserve(count);
  material.reserve(count);
  fixed.reserve(count);
}

std::size_t ParticleSet::add(const Eigen::Vector3d& position_m, double radius_m, double mass_kg,
                             int material_index, bool is_fixed) {
  position.push_back(position_m);
  velocity.push_back(Eigen::Vector3d::Zero());
  angular_velocity.push_back(Eigen::Vector3d::Zero());
  radius.push_back(radius_m);
  mass.push_back(mass_kg);
  inertia.push_back(0.4 * mass_kg * radius_m * radius_m);
  material.push_back(material_index);
  fixed.push_back(is_fixed ? 1 : 0);
  return radius.size() - 1;
}

void ParticleSet::validate() const {
  const std::size_t n = radius.size();
  if (position.size() != n || velocity.size() != n || angular_velocity.size() != n ||
      mass.size() != n || inertia.size() != n || material.size() != n || fixed.size() != n) {
    throw std::invalid_argument("ParticleSet arrays have different lengths");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string id = "particle " + std::to_string(i);
    if (!position[i].allFinite() || !velocity[i].allFinite() ||
        !angular_velocity[i].allFinite()) {
      throw std::invalid_argument(id + ": non-finite position or velocity");
    }
    if (!(radius[i] > 0.0) || !std::isfinite(radius[i])) {
      throw std::invalid_argument(id + ": radius must be positive and finite");
    }
    if (!(mass[i] > 0.0) || !std::isfinite(mass[i]) || !(inertia[i] > 0.0) ||
        !std::isfinite(inertia[i])) {
      throw std::invalid_argument(id + ": mass and inertia must be positive and finite");
    }
    if (material[i] < 0) throw std::invalid_argument(id + ": negative material index");
  }
  for (int a = 0; a < 3; ++a) {
    if (box.along(a) && !(box.length(a) > 0.0 && std::isfinite(box.length(a)) &&
                          std::isfinite(box.low[a])))
      throw std::invalid_argument("periodic axis " + std::to_string(a) + ": need low < high, finite");
  }
}

double ParticleSet::max_radius() const {
  return radius.empty() ? 0.0 : *std::max_element(radius.begin(), radius.end());
}

double ParticleSet::min_radius() const {
  return radius.empty() ? 0.0 : *std::min_element(radius.begin(), radius.end());
}

}  // namespace tmdem::mechanics
