#pragma once
// One Gauss-Seidel visit of one contact, shared by "nlgs" (GaussSeidelSolver.h) and
// "nlgs_coloured" (ColouredGaussSeidelSolver.h): the contact solves its own bipotential law
// with every other reaction frozen (closed form, CoulombCone.h) and updates its two bodies'
// velocities at once. Touches only contact c and its two bodies, so contacts that share no
// body can be visited at the same time.

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "mechanics/ContactProblem.h"
#include "mechanics/ContactSolver.h"
#include "mechanics/CoulombCone.h"

namespace tmdem::mechanics {

struct ContactUpdate {
  double change = 0.0;  // |r_c new - r_c old|, N s
  double total = 0.0;   // |r_c new|, N s
};

inline ContactUpdate gauss_seidel_update(const ContactProblem& problem, std::size_t c,
                                         double relaxation, Eigen::Vector3d& rc,
                                         std::vector<Eigen::Vector3d>& velocity,
                                         std::vector<Eigen::Vector3d>& angular_velocity) {
  const bool planar = problem.dimension == 2;
  const double w_n = problem.w_n[c], w_t = problem.w_t[c], mu = problem.mu[c];
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
  return {dr.norm(), next.norm()};
}

// Stop test and stall watch of both Gauss-Seidel solvers, fed once per sweep with the
// sweep's sums: converged when change <= tolerance * total; stalled when the residual
// change / total has not fallen below 0.9x its best over stall_sweeps sweeps.
class GaussSeidelStopTest {
 public:
  GaussSeidelStopTest(double tolerance, int stall_sweeps)
      : tolerance_(tolerance), stall_sweeps_(stall_sweeps) {}
  // Returns true when the solve should end (report.converged or report.stalled set).
  bool after_sweep(double change, double total, SolveReport& report) {
    report.residual = total > 0.0 ? change / total : 0.0;
    if (change <= tolerance_ * total) {
      report.converged = true;
      return true;
    }
    if (report.residual < 0.9 * best_) {
      best_ = report.residual;
      best_sweep_ = report.sweeps;
    } else if (report.sweeps - best_sweep_ >= stall_sweeps_) {
      report.stalled = true;
      return true;
    }
    return false;
  }

 private:
  double tolerance_;
  int stall_sweeps_;
  double best_ = std::numeric_limits<double>::infinity();
  int best_sweep_ = 0;
};

}  // namespace tmdem::mechanics
