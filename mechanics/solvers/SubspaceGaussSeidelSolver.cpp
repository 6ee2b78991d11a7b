#include "mechanics/solvers/SubspaceGaussSeidelSolver.h"

namespace tmdem::mechanics {

SubspaceGaussSeidelSolver::SubspaceGaussSeidelSolver(const SolverSettings& settings,
                                                     const ActiveSetSubspaceStep::Options& options)
    : settings_(settings), subspace_(options) {}

SolveReport SubspaceGaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                          std::vector<Eigen::Vector3d>& r,
                                                          std::vector<Eigen::Vector3d>& m,
                                                          std::vector<Eigen::Vector3d>& velocity,
                                                          std::vector<Eigen::Vector3d>& angular_velocity) {
  subspace_.start_solve();
  // After each backward sweep (a symmetric pair) a subspace step, as scheduled by
  // ActiveSetSubspaceStep::after_pair.
  struct Hooks : GaussSeidelSweepHooks {
    SubspaceGaussSeidelSolver& solver;
    void after_sweep(const GaussSeidelSweepState& state, const SolveReport& report, bool forward) {
      if (forward || report.sweeps >= solver.settings_.max_iterations) return;
      solver.subspace_.after_pair(state.problem, state.r, state.velocity, state.angular_velocity);
    }
  } hooks{{}, *this};
  GaussSeidelSweep::Options options;
  options.full_sweep_every = 1;
  options.stall_sweeps = settings_.stall_sweeps;
  const GaussSeidelSweepState state{problem, r, m, velocity, angular_velocity};
  return sweep_.solve<GaussSeidelSweep::Order::index>(settings_, options, state, hooks);
}

}  // namespace tmdem::mechanics
