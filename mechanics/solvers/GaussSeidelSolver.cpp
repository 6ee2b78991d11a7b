#include "mechanics/solvers/GaussSeidelSolver.h"

namespace tmdem::mechanics {

SolveReport GaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                  std::vector<Eigen::Vector3d>& r,
                                                  std::vector<Eigen::Vector3d>& m,
                                                  std::vector<Eigen::Vector3d>& velocity,
                                                  std::vector<Eigen::Vector3d>& angular_velocity) {
  GaussSeidelSweep::Options options;
  options.full_sweep_every = settings_.full_sweep_every;
  options.stall_sweeps = settings_.stall_sweeps;
  GaussSeidelSweepHooks hooks;
  // Slab sweeps are full sweeps: the active set's partial sweeps keep the index order.
  sliced_ = settings_.full_sweep_every == 1 &&
            slabs_.update_if_large(problem, ContactSlabs::kDefaultSlabs, settings_.parallel_from);
  if (!sliced_) {
    return sweep_.solve<GaussSeidelSweep::Order::index>(settings_, options,
                                                       {problem, r, m, velocity, angular_velocity}, hooks);
  }
  ordered_.load(problem, slabs_.order(), r, m, true);
  options.slabs = &slabs_;
  options.parallel = true;
  const SolveReport report = sweep_.solve<GaussSeidelSweep::Order::slab>(
      settings_, options, {ordered_.problem(), ordered_.r(), ordered_.m(), velocity, angular_velocity},
      hooks);
  ordered_.store(r, m, true);
  return report;
}

}  // namespace tmdem::mechanics
