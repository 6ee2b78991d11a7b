#include "mechanics/solvers/GaussSeidelSolver.h"

namespace tmdem::mechanics {

GaussSeidelSolver::GaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}

SolveReport GaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                  std::vector<Eigen::Vector3d>& r,
                                                  std::vector<Eigen::Vector3d>& m,
                                                  std::vector<Eigen::Vector3d>& velocity,
                                                  std::vector<Eigen::Vector3d>& angular_velocity) {
  GaussSeidelSweep::Options options;
  options.full_sweep_every = settings_.full_sweep_every;
  options.stall_sweeps = settings_.stall_sweeps;
  GaussSeidelSweepHooks hooks;
  return sweep_.solve<GaussSeidelSweep::Order::index>(settings_, options,
                                                     {problem, r, m, velocity, angular_velocity}, hooks);
}

}  // namespace tmdem::mechanics
