#pragma once
// One Gauss-Seidel visit of one contact, the step of every Gauss-Seidel sweep
// (GaussSeidelSweep.h: "nlgs", "nlgs_coloured", "nlgs_block", "nncg"): the contact solves its own bipotential law
// with every other reaction frozen (closed form, CoulombCone.h) and updates its two bodies'
// velocities at once. Touches only contact c and its two bodies, so contacts that share no
// body can be visited at the same time.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/ScalarVec3.h"

namespace tmdem::mechanics {

struct ContactUpdate {
  double change = 0.0;  // |r_c new - r_c old|, N s
  double total = 0.0;   // |r_c new|, N s
};

// {|d|, |x|}, the two norms the stop test adds per block (the same bits as d.norm() and
// x.norm(): both are sqrt(squaredNorm())).
inline ContactUpdate change_and_total(const ScalarVec3& d, const ScalarVec3& x) {
  return {std::sqrt(d.squared_norm()), std::sqrt(x.squared_norm())};
}

// The (n, t) block of contact c: the contact solves its bipotential law with every other
// reaction frozen (closed form, CoulombCone.h) and both bodies' velocities take the change at
// once. The kinematics run on ScalarVec3 (why: ScalarVec3.h; the same bits as on Eigen).
inline ContactUpdate gauss_seidel_update(const ContactProblem& problem, std::size_t c,
                                         double relaxation, Eigen::Vector3d& rc,
                                         std::vector<Eigen::Vector3d>& velocity,
                                         std::vector<Eigen::Vector3d>& angular_velocity) {
  const bool planar = problem.dimension == 2;
  const double w_n = problem.w_n[c], w_t = problem.w_t[c], mu = problem.mu[c];
  // u0 = U_c - W_cc r_c. A compliant contact's U_n and W_cc both carry compliance r_n, which
  // cancels here: only its local solve sees the compliance.
  const ScalarVec3 u = local_velocity<ScalarVec3>(problem, c, velocity, angular_velocity);
  const Eigen::Vector3d u0(u[0] - w_n * rc[0], u[1] - w_t * rc[1], planar ? 0.0 : u[2] - w_t * rc[2]);
  // Exact local solve (closed form of the bipotential fixed point, CoulombCone.h).
  Eigen::Vector3d next;
  solve_contact_bipotential(u0, problem.normal_delassus(c), w_t, mu, next);
  if (relaxation != 1.0) next = project_onto_coulomb_cone(rc + relaxation * (next - rc), mu);
  if (planar) next[2] = 0.0;
  const ScalarVec3 after(next), dr = after - ScalarVec3(rc);
  if (!dr.is_zero()) {
    apply_impulse(problem, c, dr, velocity, angular_velocity);
    rc = next;
  }
  ContactUpdate norms = change_and_total(dr, after);
  if (problem.stop_speed > 0.0) norms.total = std::min(norms.total, problem.stop_speed / w_n);
  return norms;
}

// The rolling block of contact c (ContactProblem::rolling), visited right after its
// (n, t) block with r_n frozen: the exact local solve of the rolling cone, with the other
// reactions frozen, m = proj_{|m| <= mu_r R_eff r_n}(m - omega_rel,t / w_r) (the block is
// w_r I on the plane perpendicular to n). Change and total are divided by R_eff, so that they
// add to the impulses' (N s) in the stop test. On ScalarVec3, as the (n, t) block.
inline ContactUpdate gauss_seidel_rolling_update(const ContactProblem& problem, std::size_t c,
                                                 double normal_impulse, Eigen::Vector3d& mc,
                                                 std::vector<Eigen::Vector3d>& angular_velocity) {
  if (problem.w_r[c] <= 0.0) return {};
  const ScalarVec3 spin = rolling_velocity<ScalarVec3>(problem, c, angular_velocity);
  const ScalarVec3 before(mc);
  const ScalarVec3 next = local_rolling_solution(problem, c, normal_impulse, before, spin);
  const ScalarVec3 dm = next - before;
  if (!dm.is_zero()) {
    apply_rolling_impulse(problem, c, dm, angular_velocity);
    next.store(mc);
  }
  const double scale = 1.0 / problem.rolling_radius[c];
  const ContactUpdate norms = change_and_total(dm, next);
  return {norms.change * scale, norms.total * scale};
}

// One visit of contact c in any Gauss-Seidel sweep: its (n, t) block, then its rolling
// block when the problem has rolling resistance (m: the rolling impulses, unused otherwise).
// An open candidate that stays open is settled first, from its normal velocity alone: with
// r_c = 0 (and m_c = 0, which r_n = 0 forces) the local solve gives 0 exactly when
// u0_n = u_n >= 0, and u_n = n . (v_i - v_j) + bias (the spins' lever terms are
// perpendicular to n). Most candidates of a look-ahead detection are such (ActiveContactSet.h).
// Always inlined: called from the sweep engine's loops (GaussSeidelSweep.h), gcc kept it out
// of line, and the call with its reloads of the problem's arrays cost 7.7% more instructions
// per sweep (callgrind, bench_solvers BM_Sweeps/0/10000/1/1: 3.84e9 against 3.56e9).
[[gnu::always_inline]] inline ContactUpdate gauss_seidel_visit(const ContactProblem& problem, std::size_t c,
                                        double relaxation, Eigen::Vector3d& rc,
                                        std::vector<Eigen::Vector3d>& m,
                                        std::vector<Eigen::Vector3d>& velocity,
                                        std::vector<Eigen::Vector3d>& angular_velocity) {
  if ((!problem.rolling || (m[c][0] == 0.0 && m[c][1] == 0.0 && m[c][2] == 0.0)) &&
      stays_open(problem, c, rc, velocity)) {
    return {};
  }
  ContactUpdate u = gauss_seidel_update(problem, c, relaxation, rc, velocity, angular_velocity);
  if (problem.rolling) {
    const ContactUpdate roll = gauss_seidel_rolling_update(problem, c, rc[0], m[c], angular_velocity);
    u.change += roll.change;
    u.total += roll.total;
  }
  return u;
}

// Stop test and stall watch of both Gauss-Seidel solvers, fed once per sweep with the
// sweep's sums: converged when change <= tolerance * total; stalled when the residual
// change / total has not fallen below 0.9x its best over stall_sweeps sweeps. Both are judged
// on full sweeps only (every_contact; ActiveContactSet.h): a partial sweep says nothing of
// the candidates it skipped. report.residual is the last sweep's change / total.
class GaussSeidelStopTest {
 public:
  GaussSeidelStopTest(double tolerance, int stall_sweeps)
      : tolerance_(tolerance), stall_sweeps_(stall_sweeps) {}
  // Returns true when the solve should end (report.converged or report.stalled set).
  bool after_sweep(double change, double total, SolveReport& report, bool every_contact = true) {
    report.residual = total > 0.0 ? change / total : 0.0;
    met_ = change <= tolerance_ * total;
    if (!every_contact) return false;
    if (met_) {
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
  // Whether the last sweep met the tolerance (a partial sweep: to be confirmed by a full one).
  bool met() const { return met_; }

 private:
  double tolerance_;
  int stall_sweeps_;
  double best_ = std::numeric_limits<double>::infinity();
  int best_sweep_ = 0;
  bool met_ = false;
};

}  // namespace tmdem::mechanics
