#pragma once
// "ipm": the contact problem solved by a primal-dual interior-point method on the bodies'
// velocities (the route of Krabbenhoft, Lyamin, Huang & Vicente 2012 and Kleinert, Simeon &
// Obermayr 2014: iteration counts nearly independent of the bed's size and depth).
//
// The convex problem. With De Saxce's slip s_c = mu_c |U_t,c| and the rolling limits held, the
// step's velocities minimise the kinetic energy of the correction,
//   min 1/2 dv^T M dv + sum_c L_c t_c
//   s.t. U~_c = U_c(dv) + s_c n in K*_c = {mu |U_t| <= U_n}   (the modified velocity, CoulombCone.h)
//        (t_c, omega_roll,c(dv)) in Q                         (t_c >= |omega_roll|: rolling)
// with dv = v - v_free and L_c = mu_r R_eff r_n,c. Its multipliers are the reactions: r_c in
// K_c for the first cones, the rolling impulse m_c (|m_c| <= L_c) for the second. The slip and
// L_c are a fixed point (the bipotential's): held while a convex problem is solved, then taken
// from its solution for the next (Cadoux's fixed point; Acary, Cadoux, Lemarechal & Malick
// 2011), the iterate kept, each slack moved inside by twice its offset's change. Updated at
// every iteration instead, they moved the problem under the iterate and the residual stalled
// near the cones' boundary (2e-3 on tall_column's first step). The first convex problem starts
// from its penalty point, not from the warm start (InteriorPointSolverSetUp.cpp, start).
// Each cone is scaled to the standard second-order cone: the friction cone's rows by
// sigma_c diag(1/mu, 1, 1), sigma_c = 1/sqrt(w_n,c), so that its slack and multiplier are both
// in sqrt(kg) m/s; a frictionless contact is a half-line.
//
// The iteration: Mehrotra's predictor-corrector with Nesterov-Todd scaling (SecondOrderCone.h);
// each iteration factorises K = M + A^T W^2 A once (the rolling t_c eliminated per contact),
// body space: symmetric positive definite for any packing, since M is, so a hyperstatic bed
// needs no regularisation, and there is no active set to chatter. CHOLMOD's supernodal
// Cholesky, its analysis reused while the pattern (the candidates' pairs of bodies) holds.
// Degrees of freedom: 6 per mobile sphere (3 in 2D), 1 per piston along its normal.
// The stop test is Siconos' residual (SiconosResidual.h) of the reactions the multipliers give,
// with the velocities those give exactly. When it stalls above the tolerance, "nncg" sweeps
// polish the best iterate (Options::polish_sweeps). When it converges, a crossover ends the
// solve: the reactions the law sets to 0 contact by contact are set to 0, then the same sweeps
// polish if Siconos' residual went above the tolerance. An interior iterate leaves every open
// candidate a little reaction, which Siconos' residual, relative to ||q|| that the candidates'
// gaps inflate, does not see, and which sent spheres off at 8 m/s on a piston's landing
// (InteriorPointSolver.cpp). The report's sweeps are the iterations plus
// the polishing sweeps. A factorisation that loses positive definiteness to round-off (W^2 of a
// stuck contact reaches 1e16 of M near the solution) is retried with 1e-12, then 1e-10, ... of
// each diagonal entry added.
// Compliant problems (mechanics.normal_law = "hertz") are refused by the registry.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <vector>

#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class InteriorPointSolver final : public ContactSolver {
 public:
  struct Options {
    int max_iterations = 200;     // interior-point iterations per solve (each one factorisation)
    double step_fraction = 0.99;  // of the step to the cones' boundary
    // A cold start's penalty kappa (InteriorPointSolver.cpp, start). On columns of 10 and 160
    // spheres from cold: 8 and 29 iterations at kappa = 1 (the deep column's multipliers start
    // far from its loads), 5 and 6 at 1e4 (the columns of test_interior_point_solver.cpp).
    double start_penalty = 1.0e4;
    // Stalled: Siconos' residual made no 10% gain over this many iterations. The slip and the
    // rolling limits move the convex problem under the iterate; near the cones' boundary the
    // interior point cannot follow them fast, and the residual stalls at 1e-7 to 1e-4.
    int stall_iterations = 8;
    // Cadoux's fixed point on the law: a convex problem counts as solved when Siconos' residual
    // with its own slip and rolling limits is this fraction of the true one; then the law is
    // taken from its solution and the next convex problem started. Stalled: no 10% gain in the
    // true residual over this many laws.
    double frozen_fraction = 0.1;
    int stall_laws = 3;
    // Then "nncg" sweeps (at most this many) polish the best iterate: the interior point has
    // carried the load through the depth, the sweeps fix the local rest (0: no polish).
    int polish_sweeps = 2000;
    // The polish checks Siconos' residual before its sweep test is met every this many sweeps
    // (SolverSettings::residual_check_every), whatever the run's own: the polish mends the
    // crossover's answer, and a check that ends it at the first residual within the tolerance
    // stops short where open candidates inflate |q| (the lattice pile with ten open copies of
    // each contact, InteriorPoint.OpenCandidatesCarryNothingWhateverTheirGaps: checked every
    // 100 sweeps, a sphere left at 2.9e-4 m/s where the test allows 9.8e-5, and the pile's
    // statics beyond the test's bound).
    int polish_residual_check_every = 250;
    // A converged answer ends with the crossover (InteriorPointSolver.cpp): the reactions the
    // law sets to 0 contact by contact set to 0, then the polishing sweeps if Siconos' residual
    // went above the tolerance. Off only to show what it mends (its test).
    bool crossover = true;
  };
  explicit InteriorPointSolver(const SolverSettings& settings);
  InteriorPointSolver(const SolverSettings& settings, const Options& options);
  ~InteriorPointSolver() override;

  std::string_view name() const override { return "ipm"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;

  long iterations() const { return iterations_total_; }
  long polish_sweeps() const { return polish_total_; }
  long laws() const { return laws_; }  // convex problems started after the first of a solve
  long regularised_factorisations() const { return regularised_; }
  long analyses() const { return analyses_; }

 private:
  struct Factor;  // CHOLMOD behind a pimpl: its header stays out of the solvers' users
  static constexpr int kMaxDofs = 12;
  // Per contact: its bodies' degrees of freedom, and per degree of freedom the columns of the
  // local velocity (n, t1, t2), of the scaled friction rows and of the scaled rolling rows
  // (entry 0, the t_c row, is zero).
  struct Columns {
    int count = 0;
    std::int32_t dof[kMaxDofs];
    Eigen::Vector3d g[kMaxDofs];
    Eigen::Vector3d friction[kMaxDofs];
    Eigen::Vector3d rolling[kMaxDofs];
  };
  void set_up(const ContactProblem& problem);
  // The law from velocity and r, then the penalty point of the convex problem it gives.
  void start(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
             const std::vector<Eigen::Vector3d>& velocity, const std::vector<Eigen::Vector3d>& angular_velocity);
  // The next law of Cadoux's fixed point, from the iterate and r, keeping the iterate.
  void next_law(const std::vector<Eigen::Vector3d>& r);
  // Slip (from dv_), rolling loads (from r), the cones' offsets h.
  void freeze_law(const std::vector<Eigen::Vector3d>& r);
  // Siconos' residual with the frozen law's slip and rolling limits: 0 at the convex solution.
  double frozen_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                         const std::vector<Eigen::Vector3d>& m, const std::vector<Eigen::Vector3d>& velocity,
                         const std::vector<Eigen::Vector3d>& angular_velocity, double q_norm) const;
  void residuals();                                // r_x, r_t, r_z at the iterate
  bool assemble_and_factorise();
  // The Newton direction for the right-hand side xi of the scaled complementarity.
  void direction(const std::vector<Eigen::Vector3d>& xi_f, const std::vector<Eigen::Vector3d>& xi_r);
  void reactions(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                 std::vector<Eigen::Vector3d>& m) const;

  SolverSettings settings_;
  Options options_;
  std::unique_ptr<Factor> factor_;
  std::unique_ptr<ContactSolver> polisher_;
  std::vector<Eigen::Vector3d> best_r_, best_m_;
  bool planar_ = false, rolling_ = false;
  std::vector<std::int32_t> first_dof_;
  std::vector<Eigen::Vector3d> piston_normal_;
  Eigen::VectorXd mass_;
  std::vector<Columns> columns_;
  // Per contact: cone dimensions (0: no cone), scales, free local and rolling velocities.
  std::vector<int> dim_f_, dim_r_;
  std::vector<double> sigma_f_, sigma_r_, mu_, rolling_limit_, slip_, load_;
  std::vector<Eigen::Vector3d> q_, q_roll_, n_dir_;
  // The iterate: x = (dv, t), slacks s and multipliers z per cone; residuals; directions.
  Eigen::VectorXd dv_, rx_, rhs_, ddv_;
  std::vector<double> t_, rt_, dt_, ktt_, rhs_t_;
  std::vector<Eigen::Vector3d> h_f_, h_r_, s_f_, z_f_, s_r_, z_r_, rz_f_, rz_r_;
  std::vector<Eigen::Vector3d> ds_f_, dz_f_, ds_r_, dz_r_, ds_fa_, dz_fa_, ds_ra_, dz_ra_;
  std::vector<Eigen::Vector3d> lambda_f_, lambda_r_, xi_f_, xi_r_, y_f_, y_r_;
  std::vector<Eigen::Matrix3d> w_f_, w_r_, winv_f_, winv_r_, w2_f_, w2_r_;
  std::vector<Eigen::Matrix<double, kMaxDofs, 1>> b_t_;  // K_dt of each rolling contact
  // K's values: where each contact's (l, k) entry (l >= k) and each diagonal entry sit.
  Eigen::SparseMatrix<double> matrix_;
  std::vector<std::int64_t> diagonal_slot_;
  std::vector<std::int64_t> block_slot_;   // kMaxDofs^2 per contact
  std::vector<std::int64_t> pattern_key_, last_key_;
  std::vector<Eigen::Triplet<double>> triplets_;
  long iterations_total_ = 0, analyses_ = 0, laws_ = 0, polish_total_ = 0, regularised_ = 0;
};

}  // namespace tmdem::mechanics
