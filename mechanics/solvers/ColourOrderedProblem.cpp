#include "mechanics/solvers/ColourOrderedProblem.h"

namespace tmdem::mechanics {

void ColourOrderedProblem::load(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                                const std::vector<Eigen::Vector3d>& m, bool parallel) {
  colouring_.update(problem);
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  const auto& order = colouring_.order();
  ordered_.dimension = problem.dimension;
  ordered_.particle_count = problem.particle_count;
  ordered_.inverse_mass.assign(problem.inverse_mass.begin(), problem.inverse_mass.end());
  ordered_.inverse_inertia.assign(problem.inverse_inertia.begin(), problem.inverse_inertia.end());
  ordered_.free_velocity.assign(problem.free_velocity.begin(), problem.free_velocity.end());
  ordered_.free_angular_velocity.assign(problem.free_angular_velocity.begin(),
                                        problem.free_angular_velocity.end());
  ordered_.rolling = problem.rolling;
  ordered_.resize_contacts(static_cast<std::size_t>(count));
  ordered_r_.resize(static_cast<std::size_t>(count));
  if (problem.rolling) ordered_m_.resize(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    const auto c = static_cast<std::size_t>(order[p]);
    ordered_.copy_contact(static_cast<std::size_t>(p), problem, c);
    ordered_r_[p] = r[c];
    if (problem.rolling) ordered_m_[p] = m[c];
  }
}

void ColourOrderedProblem::store(std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m,
                                 bool parallel) const {
  const auto count = static_cast<std::ptrdiff_t>(ordered_.size());
  const auto& order = colouring_.order();
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    r[static_cast<std::size_t>(order[p])] = ordered_r_[p];
    if (ordered_.rolling) m[static_cast<std::size_t>(order[p])] = ordered_m_[p];
  }
}

}  // namespace tmdem::mechanics
