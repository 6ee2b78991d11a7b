#pragma once
// Accelerated projected gradient with Nesterov momentum and adaptive restart (APGD, Mazhar,
// Heyn, Negrut and Tasora 2015, the scheme of Chrono), registered as "apgd". A Jacobi-type
// method: every contact of an iteration is updated from the same iterate, so the per-contact
// loops run in parallel (OpenMP) and W r comes from one body gather per iteration.
//
// The law it solves is the bipotential (non-associated) Coulomb law of CoulombCone.h, not the
// convex relaxation APGD was designed for. APGD minimises f(r) = 1/2 r.W r + b.r over the
// cones, whose optimality condition is the associated law -(W r + b) in N_K(r): sliding then
// makes the contact separate at u_n = mu |u_t| (the cone complementarity problem of Anitescu
// and Tasora). The bipotential law asks -u~ in N_K(r) with u~ = u + mu |u_t| n, i.e. u_n = 0
// while sliding. Remedy used here: a fixed point on s_c = mu |u_t,c|, the normal bias shift.
// For frozen s the problem is convex with b shifted by s n; s is refreshed from the newest
// iterate at every iteration (the "few outer iterations" merged into the inner loop), so a
// fixed point of the iteration is exactly r = proj_K(r - rho u~), the bipotential law.
// Because the objective moves with s, f is never evaluated: the step-size test only needs
// the curvature (x - y).W(x - y) <= L |x - y|^2, which does not depend on b, and the restart
// uses the gradient test g(y).(x_new - x) > 0 (O'Donoghue and Candes 2015).
//
// Metric: the Delassus diagonal D_c = diag(w_n, w_t, w_t), so that the scaled operator has a
// unit diagonal (L >= 1, about the largest number of contacts of a body); the projection in
// that metric is the projection onto the scaled cone mu' = mu sqrt(w_t / w_n).
//
// Stop test: the same measure as "nlgs" evaluated for a Jacobi pass, sum_c |r_c - R_c(r)| /
// sum_c |R_c(r)|, where R_c is the exact local solve of CoulombCone.h with the others frozen;
// R_c(r) = r_c is the bipotential law itself, so this is a natural-map residual
// (NaturalMapResidual.h) with the local step rho_c = D_c^-1. The best iterate is returned.
//
// Rolling resistance (ContactProblem::rolling): each contact has three more unknowns, its
// rolling impulse m_c, with gradient the rolling velocity and metric w_r; (r_c, m_c) is
// projected onto the Coulomb and rolling cones together (RollingCone.h: they share r_n). The
// rolling cone is non-associated in the same way (the associated law would lift a contact
// rolling at its limit by mu_r R_eff |w_roll|), and the same remedy holds: the normal bias
// shift becomes s_c = mu |u_t| + mu_r R_eff |w_roll|, so a fixed point obeys both laws with
// u_n = 0 while in contact. The stop test adds each rolling block's local solve
// (NaturalMapResidual.h, divided by R_eff), as Gauss-Seidel's does.
//
// Determinism: every reduction sums fixed blocks of contacts, then the block sums in block
// order; body velocities are gathered contact by contact in a fixed order. Results are
// therefore bitwise identical for any thread count (static schedules, no atomics).

#include <cstddef>
#include <cstdint>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class ApgdSolver final : public ContactSolver {
 public:
  // Its loops use OpenMP threads from SolverSettings::parallel_from contacts.
  explicit ApgdSolver(const SolverSettings& settings);
  std::string_view name() const override { return "apgd"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;
  // The Lipschitz estimate kept between solves.
  std::vector<double> carried_state() const override { return {lipschitz_}; }
  void restore_carried_state(const std::vector<double>& state) override {
    if (state.size() == 1) lipschitz_ = state[0];
  }

 private:
  void build_body_lists(const ContactProblem& problem);
  // velocity = v_free + M^-1 H x (+ the rolling impulses m when the problem has them), then
  // u[c] = local velocity of every contact (with bias) and spin[c] its rolling velocity.
  void local_velocities(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& x,
                        const std::vector<Eigen::Vector3d>& m,
                        std::vector<Eigen::Vector3d>& velocity,
                        std::vector<Eigen::Vector3d>& angular_velocity,
                        std::vector<Eigen::Vector3d>& u, std::vector<Eigen::Vector3d>& spin);

  SolverSettings settings_;
  std::ptrdiff_t parallel_from_;  // settings_.parallel_from, for the loops' if clauses
  double lipschitz_ = 1.0;  // of D^-1/2 W D^-1/2, kept between solves (dimensionless)

  // Reused between solves: no allocation once warm.
  std::vector<Eigen::Vector3d> x_, x_old_, y_, ux_, ux_old_, uy_, best_;
  // Rolling: impulses m (N m s) at x, x_old, y, their rolling velocities (rad/s), the best m.
  std::vector<Eigen::Vector3d> mx_, mx_old_, my_, sx_, sx_old_, sy_, mbest_;
  std::vector<BodyImpulse<Eigen::Vector3d>> impulse_;  // global p_c and n x p_c, N s
  std::vector<double> slip_bias_;                      // s_c = mu |u_t|, m/s
  std::vector<std::int32_t> body_start_, body_fill_;   // contacts of each body (CSR)
  std::vector<std::int32_t> body_contact_;             // contact index, negated-1 when j
  std::vector<double> partial_a_, partial_b_;          // per-block sums
};

}  // namespace tmdem::mechanics
