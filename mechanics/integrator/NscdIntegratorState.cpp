// NscdIntegrator::save_state / restore_state (MechanicsState.h): apart from the step so that
// the integrator's step code stays as it is.
#include <stdexcept>
#include <string>

#include "mechanics/integrator/NscdIntegrator.h"

namespace tmdem::mechanics {

MechanicsState NscdIntegrator::save_state() const {
  MechanicsState s;
  save_state(s);
  return s;
}

void NscdIntegrator::save_state(MechanicsState& s) const {
  s.position_m = particles_.position;
  s.velocity_m_per_s = particles_.velocity;
  s.angular_velocity_rad_per_s = particles_.angular_velocity;
  s.margin_m = detector_.margin();
  s.wall_margin_m = detector_.wall_margin();
  s.margin_widened_by_wall = detector_.widened_by_wall();
  s.rebuilds = std::int64_t(detector_.rebuild_count());
  s.reference_position_m = detector_.reference_positions();
  s.candidates = detector_.pairs();
  // force_ follows the table; before the first step it is shorter (no forces yet).
  s.candidate_force_N.assign(s.candidates.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < s.candidates.size() && k < force_.size(); ++k)
    s.candidate_force_N[k] = force_[k];
  s.candidate_rolling_torque_Nm.clear();
  if (rolling_) {
    s.candidate_rolling_torque_Nm.assign(s.candidates.size(), Eigen::Vector3d::Zero());
    for (std::size_t k = 0; k < s.candidates.size() && k < torque_.size(); ++k)
      s.candidate_rolling_torque_Nm[k] = torque_[k];
  }
  s.candidate_held_overlap_m = held_overlap_;
  s.solver_state = solver_->carried_state();
  s.stats = stats_;
  s.tolerance_schedule = schedule_.state();
  s.retry_limit = retry_limit_;
  s.retry_converged_in_a_row = retry_converged_in_a_row_;
  s.start_parts = start_parts_;
  s.start_parts_converged_in_a_row = start_parts_converged_in_a_row_;
  s.wall_point_m.clear();
  s.wall_velocity_m_per_s.clear();
  for (const auto& w : walls_) {
    s.wall_point_m.push_back(w.point);
    s.wall_velocity_m_per_s.push_back(w.velocity_m_per_s);
  }
  s.reference_wall_point_m = detector_.reference_wall_points();
}

void NscdIntegrator::restore_state(const MechanicsState& s) {
  const std::size_t n = particles_.size();
  if (s.position_m.size() != n || s.velocity_m_per_s.size() != n ||
      s.angular_velocity_rad_per_s.size() != n ||
      (!s.reference_position_m.empty() && s.reference_position_m.size() != n))
    throw std::invalid_argument("mechanics: a saved state of " + std::to_string(s.position_m.size()) +
                                " particles does not fit an integrator of " + std::to_string(n));
  if (s.candidate_force_N.size() != s.candidates.size())
    throw std::invalid_argument("mechanics: a saved state needs one force per candidate (" +
                                std::to_string(s.candidates.size()) + " candidates, " +
                                std::to_string(s.candidate_force_N.size()) + " forces)");
  if (!s.candidate_rolling_torque_Nm.empty() &&
      s.candidate_rolling_torque_Nm.size() != s.candidates.size())
    throw std::invalid_argument("mechanics: a saved state needs one rolling torque per candidate (" +
                                std::to_string(s.candidates.size()) + " candidates, " +
                                std::to_string(s.candidate_rolling_torque_Nm.size()) + " torques)");
  if (!s.candidate_held_overlap_m.empty() && s.candidate_held_overlap_m.size() != s.candidates.size())
    throw std::invalid_argument("mechanics: a saved state needs one held overlap per candidate (" +
                                std::to_string(s.candidates.size()) + " candidates, " +
                                std::to_string(s.candidate_held_overlap_m.size()) + " held overlaps)");
  const std::size_t w = walls_.size();
  if ((!s.wall_point_m.empty() && s.wall_point_m.size() != w) ||
      s.wall_velocity_m_per_s.size() != s.wall_point_m.size() ||
      (!s.reference_wall_point_m.empty() && s.reference_wall_point_m.size() != w))
    throw std::invalid_argument("mechanics: a saved state of " + std::to_string(s.wall_point_m.size()) +
                                " walls does not fit an integrator of " + std::to_string(w));
  for (std::size_t k = 0; k < s.wall_point_m.size(); ++k) {
    walls_[k].point = s.wall_point_m[k];
    walls_[k].velocity_m_per_s = s.wall_velocity_m_per_s[k];
  }
  particles_.position = s.position_m;
  particles_.velocity = s.velocity_m_per_s;
  particles_.angular_velocity = s.angular_velocity_rad_per_s;
  detector_.restore(s.margin_m, std::size_t(s.rebuilds), s.reference_position_m, s.candidates,
                    s.reference_wall_point_m, s.wall_margin_m,
                    s.margin_widened_by_wall);
  order_.invalidate();
  force_ = s.candidate_force_N;
  old_force_.clear();
  static_start_pending_ = false;  // the state carries its own warm start
  // A state saved without rolling torques (no rolling resistance then) starts them at 0.
  torque_ = s.candidate_rolling_torque_Nm;
  if (rolling_) torque_.resize(s.candidates.size(), Eigen::Vector3d::Zero());
  old_torque_.clear();
  held_overlap_ = s.candidate_held_overlap_m;
  holds_overlap_.clear();  // the state carries what is held
  contacts_.clear();
  schedule_.restore(s.tolerance_schedule);
  retry_limit_ = s.retry_limit;
  retry_converged_in_a_row_ = s.retry_converged_in_a_row;
  start_parts_ = s.start_parts;
  start_parts_converged_in_a_row_ = s.start_parts_converged_in_a_row;
  solver_->restore_carried_state(s.solver_state);
  stats_ = s.stats;
}

}  // namespace tmdem::mechanics
