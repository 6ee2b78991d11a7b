// NscdIntegrator's energy account and its diagnostics (kinetic and potential energy, largest
// speed, the speed a fall is judged on): read-only views of the state, apart from the step code.
#include <algorithm>
#include <cmath>
#include <functional>

#include "mechanics/integrator/NscdIntegrator.h"

namespace tmdem::mechanics {

void NscdIntegrator::account_energy(double h, StepReport& report) const {
  // Exact increments (no difference of large totals): dK = sum (m/2) (v+ - v-).(v+ + v-) (+ the
  // same for spin), dV = -sum m g . dx with dx the position update's own displacement.
  const double theta = parameters_.theta;
  double kinetic = 0.0, potential = 0.0, jump = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    const Eigen::Vector3d& v = particles_.velocity[i];
    const Eigen::Vector3d& v0 = old_velocity_[i];
    const Eigen::Vector3d& w = particles_.angular_velocity[i];
    const Eigen::Vector3d& w0 = old_angular_velocity_[i];
    const double m = particles_.mass[i], I = particles_.inertia[i];
    kinetic += 0.5 * (m * (v - v0).dot(v + v0) + I * (w - w0).dot(w + w0));
    potential -= m * gravity_.dot(h * (theta * v + (1.0 - theta) * v0));
    jump += m * (v - v0).squaredNorm() + I * (w - w0).squaredNorm();
  }
  // Pistons: their kinetic energy, and the potential of the constant external force on them
  // (load along the normal plus weight), -F . dx.
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    if (!walls_[w].moves()) continue;
    const Eigen::Vector3d& v = body_velocity_[particles_.size() + w];
    const Eigen::Vector3d& v0 = old_velocity_[particles_.size() + w];
    const double m = walls_[w].mass_kg;
    const Eigen::Vector3d force = walls_[w].load_N * walls_[w].normal + m * gravity_;
    kinetic += 0.5 * m * (v - v0).dot(v + v0);
    potential -= force.dot(h * (theta * v + (1.0 - theta) * v0));
    jump += m * (v - v0).squaredNorm();
  }
  report.energy_change_J = kinetic + potential;
  report.numerical_dissipation_J = (theta - 0.5) * jump;
}

double NscdIntegrator::kinetic_energy() const {
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    energy += 0.5 * particles_.mass[i] * particles_.velocity[i].squaredNorm() +
              0.5 * particles_.inertia[i] * particles_.angular_velocity[i].squaredNorm();
  }
  for (const auto& wall : walls_) energy += 0.5 * wall.mass_kg * wall.velocity_m_per_s * wall.velocity_m_per_s;
  return energy;
}

double NscdIntegrator::potential_energy() const {
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    energy -= particles_.mass[i] * gravity_.dot(particles_.position[i]);
  }
  for (const auto& wall : walls_) energy -= wall.mass_kg * gravity_.dot(wall.point);
  return energy;
}

double NscdIntegrator::max_speed() const {
  double speed = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    speed = std::max(speed, particles_.velocity[i].norm());
  }
  for (const auto& wall : walls_) speed = std::max(speed, std::abs(wall.velocity_m_per_s));
  return speed;
}

double NscdIntegrator::compaction_speed_m_per_s(std::size_t wall, double h) const {
  const Wall& w = walls_.at(wall);
  // Only where steps stop on Siconos' residual (nncg, nncg_ipm): the other solvers stop on the
  // change per sweep, whose residual at fall_tolerance is larger (examples/thermal_cycling.toml's
  // nncg_subspace: up to 9.4e-4), and the bed crept by itself, its lid at or above its
  // compaction speed (3.9e-4 m/s) for the whole 5 s of a re-settle.
  if (!w.moves() || !solver_settings_.siconos_stop) return 0.0;
  if (parameters_.compaction_speed) return *parameters_.compaction_speed;
  return parameters_.compaction_fraction * h * std::abs(piston_acceleration_m_per_s2(w));
}

bool NscdIntegrator::piston_compacting(double h) const {
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const double threshold = compaction_speed_m_per_s(w, h);
    if (threshold > 0.0 && std::abs(walls_[w].velocity_m_per_s) >= threshold) return true;
  }
  return false;
}

double NscdIntegrator::fall_judged_speed() const {
  speed_.clear();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] != 0.0) speed_.push_back(particles_.velocity[i].norm());
  }
  double speed = 0.0;
  if (!speed_.empty()) {
    const auto share =
        static_cast<std::size_t>(std::ceil(parameters_.fall_share * double(speed_.size())));
    const std::size_t k = std::clamp<std::size_t>(share, 1, speed_.size());
    // The k-th largest: O(n), no allocation once speed_ holds n.
    std::nth_element(speed_.begin(), speed_.begin() + std::ptrdiff_t(k - 1), speed_.end(),
                     std::greater<>());
    speed = speed_[k - 1];
  }
  for (const auto& wall : walls_) speed = std::max(speed, std::abs(wall.velocity_m_per_s));
  return speed;
}

}  // namespace tmdem::mechanics
