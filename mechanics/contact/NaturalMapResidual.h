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
#include <algorithm>
#include <cmath>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/contact/ScalarVec3.h"

namespace tmdem::mechanics {

// R_c for one contact from its reaction r_c and local velocity u (with bias, ContactProblem;
// without a compliant contact's compliance r_n).
inline Eigen::Vector3d local_law_solution(const ContactProblem& problem, std::size_t c,
                                          const Eigen::Vector3d& r_c, const Eigen::Vector3d& u) {
  const double w_n = problem.w_n[c], w_t = problem.w_t[c];
  const bool planar = problem.dimension == 2;
  const Eigen::Vector3d u0(u[0] - w_n * r_c[0], u[1] - w_t * r_c[1],
                           planar ? 0.0 : u[2] - w_t * r_c[2]);
  Eigen::Vector3d next;  // u has no compliance term, u0 needs none (GaussSeidelUpdate.h)
  solve_contact_bipotential(u0, problem.normal_delassus(c), w_t, problem.mu[c], next);
  if (planar) next[2] = 0.0;
  return next;
}

// The rolling part of R_c (ContactProblem::rolling): contact c's rolling impulse solved
// exactly with everything else frozen, normal_impulse its normal reaction, spin its rolling
// velocity (rolling_velocity, ContactKinematics.h). The block is w_r I on the plane perpendicular
// to n, so m = proj_{|m| <= mu_r R_eff r_n}(m_c - spin / w_r), kept perpendicular to n (and
// along z in 2D). 0 when the contact's bodies cannot turn (w_r = 0).
inline ScalarVec3 local_rolling_solution(const ContactProblem& problem, std::size_t c,
                                         double normal_impulse, const ScalarVec3& m_c,
                                         const ScalarVec3& spin) {
  const double w_r = problem.w_r[c];
  if (!(w_r > 0.0)) return {};
  const ScalarVec3 n(problem.normal[c]);
  ScalarVec3 next = m_c - spin / w_r;
  next = next - next.dot(n) * n;
  const double limit = problem.rolling_limit[c] * std::max(normal_impulse, 0.0);
  const double size = std::sqrt(next.squared_norm());
  // Cut to the limit with a branch, not BranchFreeMin.h's select: this branch is predictable
  // (callgrind's model mispredicts 2% of it on the 2,000 pour bed at rest), and the update
  // goes on without waiting for the square root and the quotient. The select cost 12% of a
  // sweep on the lattice pile with rolling (bench_solvers BM_Sweeps/0/10000/1/1, 1 thread:
  // 41.8 against 32.1 ns per contact) and saved 1.3% on the pour bed.
  if (size > limit) next = (size > 0.0 ? limit / size : 0.0) * next;
  if (problem.dimension == 2) next.x = next.y = 0.0;
  return next;
}
inline Eigen::Vector3d local_rolling_solution(const ContactProblem& problem, std::size_t c,
                                              double normal_impulse, const Eigen::Vector3d& m_c,
                                              const Eigen::Vector3d& spin) {
  const ScalarVec3 next =
      local_rolling_solution(problem, c, normal_impulse, ScalarVec3(m_c), ScalarVec3(spin));
  return {next.x, next.y, next.z};
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

// The same with rolling resistance (ContactProblem::rolling): m the rolling impulses, and the
// velocities include them. Each contact adds |m_c - M_c| and |M_c| divided by R_eff (impulses,
// N s), M_c = local_rolling_solution with R_c's normal reaction, as Gauss-Seidel's stop test.
double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& m,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity);

}  // namespace tmdem::mechanics
