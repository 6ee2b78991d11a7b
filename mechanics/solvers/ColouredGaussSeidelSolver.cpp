#include "mechanics/solvers/ColouredGaussSeidelSolver.h"

namespace tmdem::mechanics {

SolveReport ColouredGaussSeidelSolver::solve_with_rolling(
    const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
    std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
    std::vector<Eigen::Vector3d>& angular_velocity) {
  const bool parallel = static_cast<std::ptrdiff_t>(problem.size()) >= settings_.parallel_from;
  ordered_.load(problem, r, m, parallel);
  GaussSeidelSweep::Options options;
  options.full_sweep_every = settings_.full_sweep_every;
  options.stall_sweeps = settings_.stall_sweeps;
  options.colour_start = &ordered_.colour_start();
  options.parallel = parallel;
  GaussSeidelSweepHooks hooks;
  const SolveReport report = sweep_.solve<GaussSeidelSweep::Order::colour>(
      settings_, options,
      {ordered_.problem(), ordered_.r(), ordered_.m(), velocity, angular_velocity}, hooks);
  ordered_.store(r, m, parallel);
  return report;
}

}  // namespace tmdem::mechanics
