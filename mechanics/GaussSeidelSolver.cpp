#include "mechanics/GaussSeidelSolver.h"

#include "mechanics/GaussSeidelUpdate.h"

namespace tmdem::mechanics {

GaussSeidelSolver::GaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}

SolveReport GaussSeidelSolver::solve(const ContactProblem& problem,
                                     std::vector<Eigen::Vector3d>& r,
                                     std::vector<Eigen::Vector3d>& velocity,
                                     std::vector<Eigen::Vector3d>& angular_velocity) {
  return solve_with_rolling(problem, r, no_rolling_, velocity, angular_velocity);
}

SolveReport GaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                  std::vector<Eigen::Vector3d>& r,
                                                  std::vector<Eigen::Vector3d>& m,
                                                  std::vector<Eigen::Vector3d>& velocity,
                                                  std::vector<Eigen::Vector3d>& angular_velocity) {
  problem.velocities_from_reactions(r, velocity, angular_velocity);
  if (problem.rolling) problem.add_rolling_impulses(m, angular_velocity);
  const std::size_t count = problem.size();
  SolveReport report;
  GaussSeidelStopTest stop(settings_.tolerance, settings_.stall_sweeps);
  while (report.sweeps < settings_.max_iterations) {
    ++report.sweeps;
    double change = 0.0, total = 0.0;
    // Symmetric Gauss-Seidel: sweeps alternate forward and backward through the contacts,
    // so that a load travels the whole length of a chain (a column, a force path) in one
    // pair of sweeps whichever way the contacts happen to be numbered.
    const bool forward = report.sweeps % 2 == 1;
    for (std::size_t visit = 0; visit < count; ++visit) {
      const std::size_t c = forward ? visit : count - 1 - visit;
      if (!problem.solvable(c)) continue;
      const ContactUpdate u =
          gauss_seidel_visit(problem, c, settings_.relaxation, r[c], m, velocity, angular_velocity);
      change += u.change;
      total += u.total;
    }
    if (stop.after_sweep(change, total, report)) break;
  }
  return report;
}

}  // namespace tmdem::mechanics
