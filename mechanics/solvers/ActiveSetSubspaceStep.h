#pragma once
// The subspace step of "nlgs_subspace" (SubspaceGaussSeidelSolver.h) and "nncg_subspace"
// (NncgSolver.h): from reactions a Gauss-Seidel sweep pair left, a direct solve of the contacts
// that are closed (the PGS-SM of Silcowitz, Niebe and Erleben, "Projected Gauss-Seidel subspace
// minimization method for interactive rigid body dynamics", GRAPP 2010, adapted to the
// Coulomb cone). Once the sweeps have found which contacts are closed, sticking or sliding, the
// rest is linear:
//   W_AA dr_A = -U_A
// where U_A are the current local velocities of the active unknowns (bias included, hence the
// coupling to every reaction held fixed) and W_AA = H_A^T M^-1 H_A the Delassus operator
// restricted to them, assembled sparse (3x3 blocks between contacts sharing a mobile body; a
// piston takes normal impulses only, ContactKinematics.h):
//   - sticking contacts (r_n > 0, |r_t| < stick_fraction mu r_n): all three components (two in
//     2D), u_c = 0;
//   - sliding contacts (|r_t| = mu r_n to round-off): the normal component only, u_n = 0, the
//     tangential impulse held in its direction and rescaled to mu r_n afterwards;
//   - open contacts that are closing or resting (r = 0, u_n <= 1e-9 of the fastest free speed:
//     the load the sweeps have not carried to them yet): the normal component only; the
//     projection leaving one open is no change of status;
//   - open contacts (r_n = 0), contacts just inside the cone's edge and the rolling impulses
//     (ContactProblem::rolling) are held fixed (the sweeps solve them).
// A compliant problem (ContactProblem::compliance, the "hertz" normal law) solves with
// W_AA + C_A, C_A its active contacts' normal compliances, and U_A includes C r_n: positive
// definite, its forces unique. A rigid hyperstatic bed makes W_AA singular, and the position terms of a closed loop of contacts
// can make W_AA dr = -U_A inconsistent; the step is therefore the proximal point iteration
// (W_AA + rho D) (x_{k+1} - x_k) = -U_A(x_k), D = diag(W_AA), a few passes from x = 0
// (Options::proximal, proximal_iterations): bounded in the near-null directions, and any
// admissible solution is fine (a rigid hyperstatic bed's forces are not unique). The result is
// projected onto the cones along a short line search (r_A + alpha x, alpha = 1, 1/2, 1/4), kept
// at the first alpha that lowers the natural-map residual (NaturalMapResidual.h, without the
// rolling blocks); when the projection changed a contact's status the step is repeated on the
// new active set (Options::active_passes). A step that lowers nothing leaves the reactions and
// velocities exactly as they were, and the next step waits twice as many pairs (at most 64).
//
// Allocation: the active set's arrays, the sparse matrix and its factorisation are members,
// reused from step to step and solve to solve. When the active set keeps its pattern (the same
// contacts, bodies and statuses) only the values are refilled and refactorised; a new pattern
// rebuilds the matrix (Eigen's setFromTriplets and analyzePattern allocate). Eigen's
// SimplicialLDLT allocates small temporaries in factorize and solve.

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

class ActiveSetSubspaceStep {
 public:
  struct Options {
    int proximal_iterations = 8;   // proximal passes per active set (fewer once U_A is solved)
    double proximal = 1e-10;        // rho, relative to the diagonal of W_AA
    int active_passes = 3;         // re-solves after the projection changed a contact's status
    double stick_fraction = 0.9;   // sticking below this fraction of the cone; held up to the edge
    int line_search_steps = 3;     // step lengths tried per pass: 1, 1/2, 1/4
  };
  static constexpr int kMaxWait = 64;  // sweep pairs between steps after repeated rejections

  ActiveSetSubspaceStep() : ActiveSetSubspaceStep(Options{}) {}
  explicit ActiveSetSubspaceStep(const Options& options);

  // The start of a solve: counters and schedule reset (the pattern is kept).
  void start_solve();
  // After a sweep pair: a step when the schedule says so; true if it changed r (and the
  // velocities with it, v = v_free + M^-1 H r kept).
  bool after_pair(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                  std::vector<Eigen::Vector3d>& velocity, std::vector<Eigen::Vector3d>& angular_velocity);
  // One step now; true if kept.
  bool take(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
            std::vector<Eigen::Vector3d>& velocity, std::vector<Eigen::Vector3d>& angular_velocity);

  // Since start_solve: steps tried, kept, symbolic factorisations (new patterns) and numeric ones.
  int tried() const { return tried_; }
  int accepted() const { return accepted_; }
  int patterns() const { return patterns_; }
  int factorisations() const { return factorisations_; }

 private:
  // The active set of r into active_, offset_, size_; false when it is empty.
  bool classify(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                const std::vector<Eigen::Vector3d>& velocity);
  // W_AA + rho D into matrix_ (a new pattern when the active set's changed) and factorised.
  bool assemble_and_factorise(const ContactProblem& problem);
  // Calls emit(row, col, value) for every lower-triangle contribution to W_AA, in a fixed order.
  template <class Emit>
  void for_each_contribution(const ContactProblem& problem, Emit&& emit) const;

  Options options_;
  // The active set: contacts, their first unknown and number of unknowns (3 or 2 in 2D:
  // sticking; 1: sliding), and for comparing patterns the bodies of each.
  std::vector<std::int32_t> active_, offset_, size_, pattern_key_, last_key_;
  std::vector<std::int32_t> body_start_, body_entries_;  // CSR: per body, its active contacts
  std::vector<std::int32_t> cursor_;  // per body, where its next entry goes
  // Per active contact and side (0: i, 1: j): the body's velocity change per unit local impulse
  // (linear L, angular A, columns n, t1, t2; inverse mass and inertia not applied).
  std::vector<Eigen::Matrix3d> linear_[2], angular_[2];
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<std::int32_t> value_index_;     // per contribution, its slot in matrix_'s values
  std::vector<std::int32_t> diagonal_index_;  // per unknown, its diagonal slot
  Eigen::SparseMatrix<double> matrix_;        // lower triangle of W_AA + rho D
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> factor_;
  bool have_pattern_ = false;
  Eigen::VectorXd diagonal_, x_, residual_, step_, product_;
  // The reactions and velocities before the step, restored when it is rejected; per active
  // contact its reaction at the start of a pass.
  std::vector<Eigen::Vector3d> saved_r_, saved_v_, saved_w_, pass_start_;
  int tried_ = 0, accepted_ = 0, patterns_ = 0, factorisations_ = 0;
  int wait_ = 1, waited_ = 0;  // sweep pairs to wait before the next step, and waited so far
};

}  // namespace tmdem::mechanics
