#include "mechanics/solvers/GaussSeidelSolver.h"

#include "mechanics/solvers/GaussSeidelUpdate.h"

namespace tmdem::mechanics {

GaussSeidelSolver::GaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}

SolveReport GaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                  std::vector<Eigen::Vector3d>& r,
                                                  std::vector<Eigen::Vector3d>& m,
                                                  std::vector<Eigen::Vector3d>& velocity,
                                                  std::vector<Eigen::Vector3d>& angular_velocity) {
  problem.velocities_from_reactions(r, m, velocity, angular_velocity);
  const std::size_t count = problem.size();
  SolveReport report;
  GaussSeidelStopTest stop(settings_.tolerance, settings_.stall_sweeps);
  active_.start(count, settings_.full_sweep_every, settings_.max_iterations);
  while (report.sweeps < settings_.max_iterations) {
    ++report.sweeps;
    double change = 0.0, total = 0.0;
    // Symmetric Gauss-Seidel: sweeps alternate forward and backward through the contacts,
    // so that a load travels the whole length of a chain (a column, a force path) in one
    // pair of sweeps whichever way the contacts happen to be numbered.
    const bool forward = report.sweeps % 2 == 1;
    const bool full = active_.full(report.sweeps);
    const bool mark = full && active_.partial_sweeps();  // else nothing reads the marks
    // Full sweeps visit every contact and mark the passive ones, partial sweeps the active
    // ones only, in the same relative order (ActiveContactSet.h).
    const std::size_t visits = full ? count : active_.active().size();
    for (std::size_t visit = 0; visit < visits; ++visit) {
      const std::size_t k = forward ? visit : visits - 1 - visit;
      const std::size_t c = full ? k : static_cast<std::size_t>(active_.active()[k]);
      if (!problem.solvable(c)) {
        if (mark) active_.mark_unsolvable(c);
        continue;
      }
      const ContactUpdate u =
          gauss_seidel_visit(problem, c, settings_.relaxation, r[c], m, velocity, angular_velocity);
      change += u.change;
      total += u.total;
      if (mark) active_.mark_visited(c, u.total);
    }
    if (stop.after_sweep(change, total, report, full)) break;
    if (mark) active_.collect(count);
    active_.after_sweep(full, stop.met());
  }
  return report;
}

}  // namespace tmdem::mechanics
