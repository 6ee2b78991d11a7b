#include "mechanics/solvers/ColouredGaussSeidelSolver.h"

namespace tmdem::mechanics {

ColouredGaussSeidelSolver::ColouredGaussSeidelSolver(const SolverSettings& settings,
                                                     std::ptrdiff_t parallel_from)
    : settings_(settings), parallel_from_(parallel_from) {}

SolveReport ColouredGaussSeidelSolver::solve_with_rolling(
    const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
    std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
    std::vector<Eigen::Vector3d>& angular_velocity) {
  colouring_.update(problem);
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  const auto& order = colouring_.order();
  const bool parallel = count >= parallel_from_;
  // The problem in colour order: contact p of ordered_ is contact order[p] of problem.
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
  GaussSeidelSweep::Options options;
  options.full_sweep_every = settings_.full_sweep_every;
  options.stall_sweeps = settings_.stall_sweeps;
  options.colour_start = &colouring_.start();
  options.parallel = parallel;
  GaussSeidelSweepHooks hooks;
  const SolveReport report =
      sweep_.solve<GaussSeidelSweep::Order::colour>(
          settings_, options, {ordered_, ordered_r_, ordered_m_, velocity, angular_velocity}, hooks);
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    r[static_cast<std::size_t>(order[p])] = ordered_r_[p];
    if (problem.rolling) m[static_cast<std::size_t>(order[p])] = ordered_m_[p];
  }
  return report;
}

}  // namespace tmdem::mechanics
