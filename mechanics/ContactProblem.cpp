#include "mechanics/ContactProblem.h"

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
}

void ContactProblem::velocities_from_reactions(const std::vector<Eigen::Vector3d>& r,
                                               std::vector<Eigen::Vector3d>& velocity,
                                               std::vector<Eigen::Vector3d>& angular_velocity) const {
  velocity.assign(free_velocity.begin(), free_velocity.end());
  angular_velocity.assign(free_angular_velocity.begin(), free_angular_velocity.end());
  for (std::size_t c = 0; c < size(); ++c) {
    if (r[c][0] > 0.0) apply_impulse(c, r[c], velocity, angular_velocity);
  }
}

}  // namespace tmdem::mechanics
