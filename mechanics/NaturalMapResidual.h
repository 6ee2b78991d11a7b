#pragma once
// How far reactions are from solving the contact problem, one scale-free number: the
// natural-map residual of the bipotential law with the local step rho_c = W_cc^-1,
//   sum_c | r_c - R_c(r) |  /  sum_c | R_c(r) |     (0 when both sums are 0, 1 when only
//                                                    the denominator is)
// where R_c(r) is the exact local solve of contact c with every other reaction frozen
// (CoulombCone.h). R_c(r) = r_c is the law itself; |r_c - R_c(r)| is what one Jacobi pass
// would change, so the measure is the Jacobi form of Gauss-Seidel's "change over total" and
// lets any two solvers be compared on the same footing (bench, tests).

#include <Eigen/Core>
#include <vector>

#include "mechanics/ContactProblem.h"
#include "mechanics/CoulombCone.h"

namespace tmdem::mechanics {

// R_c for one contact from its reaction r_c and local velocity u (with bias, ContactProblem).
inline Eigen::Vector3d local_law_solution(const ContactProblem& problem, std::size_t c,
                                          const Eigen::Vector3d& r_c, const Eigen::Vector3d& u) {
  const double w_n = problem.w_n[c], w_t = problem.w_t[c];
  const bool planar = problem.dimension == 2;
  const Eigen::Vector3d u0(u[0] - w_n * r_c[0], u[1] - w_t * r_c[1],
                           planar ? 0.0 : u[2] - w_t * r_c[2]);
  Eigen::Vector3d next;
  solve_contact_bipotential(u0, w_n, w_t, problem.mu[c], next);
  if (planar) next[2] = 0.0;
  return next;
}

// The ratio above from its two sums.
inline double natural_map_ratio(double defect, double total) {
  if (total > 0.0) return defect / total;
  return defect > 0.0 ? 1.0 : 0.0;
}

// The residual above for reactions r and the body velocities they give (v_free + M^-1 H r).
double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity);

}  // namespace tmdem::mechanics
