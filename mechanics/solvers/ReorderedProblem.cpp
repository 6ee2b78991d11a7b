#include "mechanics/solvers/ReorderedProblem.h"

namespace tmdem::mechanics {

void ReorderedProblem::load(const ContactProblem& problem, const std::vector<std::int32_t>& order,
                            const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& m, bool parallel) {
  order_.assign(order.begin(), order.end());
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  ordered_.dimension = problem.dimension;
  ordered_.particle_count = problem.particle_count;
  ordered_.inverse_mass.assign(problem.inverse_mass.begin(), problem.inverse_mass.end());
  ordered_.inverse_inertia.assign(problem.inverse_inertia.begin(), problem.inverse_inertia.end());
  ordered_.free_velocity.assign(problem.free_velocity.begin(), problem.free_velocity.end());
  ordered_.free_angular_velocity.assign(problem.free_angular_velocity.begin(),
                                        problem.free_angular_velocity.end());
  ordered_.rolling = problem.rolling;
  ordered_.compliant = problem.compliant;
  ordered_.stop_speed = problem.stop_speed;
  ordered_.resize_contacts(static_cast<std::size_t>(count));
  ordered_r_.resize(static_cast<std::size_t>(count));
  if (problem.rolling) ordered_m_.resize(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    const auto c = static_cast<std::size_t>(order_[static_cast<std::size_t>(p)]);
    ordered_.copy_contact(static_cast<std::size_t>(p), problem, c);
    ordered_r_[p] = r[c];
    if (problem.rolling) ordered_m_[p] = m[c];
  }
}

void ReorderedProblem::store(std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m,
                             bool parallel) const {
  const auto count = static_cast<std::ptrdiff_t>(ordered_.size());
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    const auto c = static_cast<std::size_t>(order_[static_cast<std::size_t>(p)]);
    r[c] = ordered_r_[p];
    if (ordered_.rolling) m[c] = ordered_m_[p];
  }
}

}  // namespace tmdem::mechanics
