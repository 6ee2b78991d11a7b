#include "coupling/run/SettleRestTest.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "mechanics/model/PairIndex.h"

namespace tmdem::coupling {

SettleRestTest::SettleRestTest(SettleRestTestSettings settings)
    : settings_(settings), force_change_(std::numeric_limits<double>::infinity()) {
  if (settings_.window_steps < 1)
    throw std::invalid_argument("mechanics.rest_window must be >= 1");
  if (!(settings_.force_change > 0.0))
    throw std::invalid_argument("mechanics.rest_force_change must be > 0");
  if (!(settings_.speed_m_s > 0.0)) throw std::invalid_argument("mechanics.settle_velocity must be > 0");
}

void SettleRestTest::restore_history(std::deque<Snapshot> history) {
  if (history.size() > std::size_t(settings_.window_steps) + 1)
    throw std::invalid_argument("settle rest test: " + std::to_string(history.size()) +
                                " saved steps, more than the window of " +
                                std::to_string(settings_.window_steps) + " steps holds");
  for (const auto& s : history)
    if (s.pair.size() != s.normal_force_N.size())
      throw std::invalid_argument("settle rest test: a saved step has " + std::to_string(s.pair.size()) +
                                  " contacts but " + std::to_string(s.normal_force_N.size()) + " forces");
  history_ = std::move(history);
}

double SettleRestTest::force_difference_N(const Snapshot& a, const Snapshot& b) {
  double sum = 0.0;
  std::size_t i = 0, k = 0;
  while (i < a.pair.size() || k < b.pair.size()) {
    if (k == b.pair.size() || (i < a.pair.size() && a.pair[i] < b.pair[k])) {
      sum += a.normal_force_N[i++];
    } else if (i == a.pair.size() || b.pair[k] < a.pair[i]) {
      sum += b.normal_force_N[k++];
    } else {
      sum += std::abs(a.normal_force_N[i++] - b.normal_force_N[k++]);
    }
  }
  return sum;
}

bool SettleRestTest::after_step(const std::vector<mechanics::ContactForce>& contacts,
                                const mechanics::ParticleSet& particles) {
  // Reuse the oldest snapshot's storage once the window is full: no allocation when warm.
  Snapshot now;
  if (history_.size() == std::size_t(settings_.window_steps) + 1) {
    now = std::move(history_.front());
    history_.pop_front();
  }
  now.pair.clear();
  now.normal_force_N.clear();
  contact_force_N_.assign(particles.size(), 0.0);
  pressed_N_.assign(particles.size(), 0.0);
  const double gravity = settings_.gravity_m_s2.norm();
  const Eigen::Vector3d down = gravity > 0.0 ? Eigen::Vector3d(settings_.gravity_m_s2 / gravity)
                                             : Eigen::Vector3d::Zero();
  double total_N = 0.0;
  for (const auto& c : contacts) {
    now.pair.emplace_back(c.i, c.j);
    now.normal_force_N.push_back(c.normal_force_N);
    total_N += c.normal_force_N;
    // On i; j takes the opposite.
    const double along_gravity_N = (c.normal_force_N * c.normal + c.tangential_force_N).dot(down);
    contact_force_N_[std::size_t(c.i)] += c.normal_force_N;
    pressed_N_[std::size_t(c.i)] += std::max(along_gravity_N, 0.0);
    if (!mechanics::is_wall(c.j)) {
      contact_force_N_[std::size_t(c.j)] += c.normal_force_N;
      pressed_N_[std::size_t(c.j)] += std::max(-along_gravity_N, 0.0);
    }
  }
  history_.push_back(std::move(now));

  // Pressed by at least half its weight: passes load on. Where nobody is, every particle held
  // by half its weight counts (a single layer on a floor, no gravity).
  bool any_pressed = false;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!particles.fixed[p] && pressed_N_[p] > 0.0 &&
        pressed_N_[p] >= 0.5 * particles.mass[p] * gravity) {
      any_pressed = true;
      break;
    }
  double kinetic_2J = 0.0, mass_kg = 0.0;  // 2 KE and M of the load carriers
  double max_speed_m_s = 0.0;
  rattlers_ = 0;
  load_carriers_ = 0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    if (particles.fixed[p]) continue;
    max_speed_m_s = std::max(max_speed_m_s, particles.velocity[p].norm());
    const double half_weight_N = 0.5 * particles.mass[p] * gravity;
    const double force_N = contact_force_N_[p];
    if (!(force_N > 0.0 && force_N >= half_weight_N)) {
      ++rattlers_;
      continue;
    }
    if (any_pressed && !(pressed_N_[p] > 0.0 && pressed_N_[p] >= half_weight_N)) continue;
    ++load_carriers_;
    kinetic_2J += particles.mass[p] * particles.velocity[p].squaredNorm();
    mass_kg += particles.mass[p];
  }
  load_speed_m_s_ = mass_kg > 0.0 ? std::sqrt(kinetic_2J / mass_kg) : 0.0;

  if (history_.size() < std::size_t(settings_.window_steps) + 1) return false;
  // No force anywhere (no gravity, nothing pressed): nothing carries load, so every particle
  // must be still, as the velocity test asks.
  if (total_N == 0.0) {
    force_change_ = 0.0;
    return max_speed_m_s < settings_.speed_m_s;
  }
  force_change_ = force_difference_N(history_.front(), history_.back()) / total_N;
  return force_change_ < settings_.force_change && load_speed_m_s_ < settings_.speed_m_s;
}

}  // namespace tmdem::coupling
