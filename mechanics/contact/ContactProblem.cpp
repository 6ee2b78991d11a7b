#include "mechanics/contact/ContactProblem.h"

#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

void ContactProblem::resize_contacts(std::size_t count) {
  body_i.resize(count);
  body_j.resize(count);
  normal.resize(count);
  tangent1.resize(count);
  tangent2.resize(count);
  lever_i.resize(count);
  lever_j.resize(count);
  w_n.resize(count);
  w_t.resize(count);
  bias.resize(count);
  mu.resize(count);
  if (compliant) compliance.resize(count);
  if (rolling) {
    rolling_limit.resize(count);
    rolling_radius.resize(count);
    w_r.resize(count);
  }
}

void ContactProblem::add_rolling_impulses(const std::vector<Eigen::Vector3d>& m,
                                          std::vector<Eigen::Vector3d>& angular_velocity) const {
  for (std::size_t c = 0; c < size(); ++c) {
    if (m[c][0] != 0.0 || m[c][1] != 0.0 || m[c][2] != 0.0) apply_rolling_impulse(*this, c, m[c], angular_velocity);
  }
}

void ContactProblem::velocities_from_reactions(const std::vector<Eigen::Vector3d>& r,
                                               std::vector<Eigen::Vector3d>& velocity,
                                               std::vector<Eigen::Vector3d>& angular_velocity) const {
  velocity.assign(free_velocity.begin(), free_velocity.end());
  angular_velocity.assign(free_angular_velocity.begin(), free_angular_velocity.end());
  for (std::size_t c = 0; c < size(); ++c) {
    if (r[c][0] > 0.0) apply_impulse(*this, c, r[c], velocity, angular_velocity);
  }
}

}  // namespace tmdem::mechanics
