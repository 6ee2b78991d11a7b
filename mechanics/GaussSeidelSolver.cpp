#include "mechanics/GaussSeidelSolver.h"

#include <limits>

#include "mechanics/CoulombCone.h"

namespace tmdem::mechanics {

GaussSeidelSolver::GaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}

SolveReport GaussSeidelSolver::solve(const ContactProblem& problem,
                                     std::vector<Eigen::Vector3d>& r,
                                     std::vector<Eigen::Vector3d>& velocity,
                                     std::vector<Eigen::Vector3d>& angular_velocity) {
  problem.velocities_from_reactions(r, velocity, angular_velocity);
  const bool planar = problem.dimension == 2;
  const double relaxation = settings_.relaxation;
  const std::size_t count = problem.size();
  SolveReport report;
  // Stall watch: the best residual so far and the sweep at which it last fell by 10%.
  double best = std::numeric_limits<double>::infinity();
  int best_sweep = 0;
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
      const double w_n = problem.w_n[c], w_t = problem.w_t[c], mu = problem.mu[c];
      Eigen::Vector3d& rc = r[c];
      // Local velocity without this contact's own reaction: u0 = U - W_cc r_c.
      const Eigen::Vector3d u = problem.local_velocity(c, velocity, angular_velocity);
      const Eigen::Vector3d u0(u[0] - w_n * rc[0], u[1] - w_t * rc[1],
                               planar ? 0.0 : u[2] - w_t * rc[2]);
      // Exact local solve (closed form of the bipotential fixed point, CoulombCone.h).
      Eigen::Vector3d next;
      solve_contact_bipotential(u0, w_n, w_t, mu, next);
      if (relaxation != 1.0) next = project_onto_coulomb_cone(rc + relaxation * (next - rc), mu);
      if (planar) next[2] = 0.0;
      const Eigen::Vector3d dr = next - rc;
      if (dr[0] != 0.0 || dr[1] != 0.0 || dr[2] != 0.0) {
        problem.apply_impulse(c, dr, velocity, angular_velocity);
        rc = next;
      }
      change += dr.norm();
      total += next.norm();
    }
    report.residual = total > 0.0 ? change / total : 0.0;
    if (change <= settings_.tolerance * total) {
      report.converged = true;
      break;
    }
    if (report.residual < 0.9 * best) {
      best = report.residual;
      best_sweep = report.sweeps;
    } else if (report.sweeps - best_sweep >= settings_.stall_sweeps) {
      report.stalled = true;
      break;
    }
  }
  return report;
}

}  // namespace tmdem::mechanics
