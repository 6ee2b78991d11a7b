#pragma once
// The interface every contact solver implements: it takes a ContactProblem and the
// warm-start reactions, and returns the reactions and the body velocities they give.
// Solvers are chosen by name (mechanics.solver) through ContactSolverRegistry.h.
//
// What a solver may use from the problem: its kinematics (ContactKinematics.h: local_velocity,
// H^T v + bias; apply_impulse), velocities_from_reactions (v = v_free + M^-1 H r, so W r = H^T (v(r) - v_free)), the
// Delassus diagonal blocks (w_n, w_t), the local law (CoulombCone.h: projection onto the
// cone and the closed-form local solve) and ContactResidual.h for the stop test.

#include <Eigen/Core>
#include <cassert>
#include <string_view>
#include <vector>

#include "mechanics/model/ParallelFrom.h"
#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

struct SolverSettings {
  double tolerance = 1.0e-6;  // stop when the solver's residual is at most this
  int max_iterations = 10000; // sweeps (or iterations) per solve
  double relaxation = 1.0;    // over-relaxation factor, where the solver has one
  int stall_sweeps = 500;     // stop when the residual made no progress over this many sweeps
  // Gauss-Seidel solvers: a sweep over every contact at least every this many sweeps, the
  // others visit the active contacts only (ActiveContactSet.h); 1: every sweep is full.
  int full_sweep_every = 1;
  // "nncg": a solve its own stop test calls converged goes on (tighter) until Siconos' residual
  // (SiconosResidual.h) is within `tolerance` too (scene mechanics.stop_test = "siconos", the
  // default; NscdIntegrator sets it for "nncg" only).
  bool siconos_stop = false;
  // "nncg" with siconos_stop: Siconos' residual every this many sweeps before its sweep test is
  // met, the solve ending once it is within `tolerance` (0: never; -1: the solver's own default,
  // NncgSolver::Options::siconos_check_unmet_every).
  int residual_check_every = -1;
  // Contacts from which the solvers use OpenMP threads, and "nlgs" and "nncg" sweep slab by slab
  // (ContactSlabs::update_if_large): NscdParameters::parallel_from.
  std::ptrdiff_t parallel_from = kDefaultParallelFrom;
};

struct SolveReport {
  int sweeps = 0;          // iterations used
  double residual = 0.0;   // at the last iteration (meaning: see the solver)
  bool converged = false;  // residual <= tolerance within max_iterations
  bool stalled = false;    // stopped early: no progress over stall_sweeps (not converged)
  // A solver that hands what its first solver left unconverged to later stages
  // (FallbackContactSolver.h): the last stage that ran (kNoFallback: none; the solve ended by it,
  // converged or not; kWithinWhenHandedOn, whichever stage ended it: the first solver's reactions
  // were within the tolerance by Siconos' measure already, its own stop test unmet), the
  // iterations of the stages after the first (in `sweeps` too) and their wall time, s (where the
  // default solver's time goes: docs/summary.md, mechanics.fallback).
  static constexpr int kNoFallback = 0, kSecondSolver = 1, kFirstAgain = 2, kPlainSweeps = 3,
                       kWithinWhenHandedOn = 4;
  int fallback_stage = kNoFallback;
  int fallback_sweeps = 0;
  double fallback_s = 0.0;
  // On a solve handed on: the first solver's own iterations and wall time, s, before it handed
  // it on (what handing on sooner could save).
  int fallback_first_sweeps = 0;
  double fallback_first_s = 0.0;
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  virtual std::string_view name() const = 0;

  // r: one local impulse per contact (N s, frame n, t1, t2): the warm start on entry (already
  // inside its Coulomb cone, zero for unsolvable contacts), the reactions on return.
  // m: one rolling angular impulse per contact (N m s, global; ContactProblem.h) when the
  // problem has rolling resistance (ContactProblem::rolling), the warm start on entry (within
  // its rolling cone), the rolling reactions on return; not read otherwise.
  // velocity, angular_velocity: one per body, overwritten with v_free + M^-1 H r on return.
  // Must not allocate once warm (the step loop calls it every step). Every solver handles
  // rolling resistance.
  virtual SolveReport solve_with_rolling(const ContactProblem& problem,
                                         std::vector<Eigen::Vector3d>& r,
                                         std::vector<Eigen::Vector3d>& m,
                                         std::vector<Eigen::Vector3d>& velocity,
                                         std::vector<Eigen::Vector3d>& angular_velocity) = 0;

  // A problem without rolling resistance (the m above is never read).
  SolveReport solve(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                    std::vector<Eigen::Vector3d>& velocity,
                    std::vector<Eigen::Vector3d>& angular_velocity) {
    assert(!problem.rolling && "a problem with rolling resistance needs solve_with_rolling");
    return solve_with_rolling(problem, r, no_rolling_, velocity, angular_velocity);
  }

  // What the solver carries from one solve to the next (e.g. a step-size estimate), as plain
  // numbers, and putting it back (restart from a checkpoint: MechanicsState.h). Empty for a
  // solver that starts every solve from the warm-start reactions alone.
  virtual std::vector<double> carried_state() const { return {}; }
  // Whether the solver hands unconverged solves on to later stages (SolveReport::fallback_stage).
  virtual bool has_fallback() const { return false; }
  // Whether the solves that follow may be handed on (default: yes). The integrator withholds the
  // later stages on a try of a step that a retry in shorter parts would follow
  // (NscdParameters::fallback_on_last_try).
  virtual void set_hand_on(bool /*allowed*/) {}
  virtual void restore_carried_state(const std::vector<double>& /*state*/) {}

 private:
  std::vector<Eigen::Vector3d> no_rolling_;  // m of a problem without rolling (never read)
};

}  // namespace tmdem::mechanics
