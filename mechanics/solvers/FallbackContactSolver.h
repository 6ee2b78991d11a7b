#pragma once
// A contact solver that hands the steps its first solver does not converge to a second one,
// started from the first one's reactions ("nncg_ipm": nncg, then the interior point). Where the
// first converges, the result is the first's, to the bit: the fallback costs nothing on the
// steps that never needed it. The second runs only on problems up to a size, and its result is
// kept only if it is nearer the law than the first's. Compliant problems are the first solver's alone (ContactSolverRegistry
// lists "nncg_ipm" as taking them: it is "nncg" there).
// A near miss (neither converged, the better within near_miss x the tolerance of Siconos'
// residual) gets the first solver once more from the better reactions, its own budget again,
// kept if nearer the law: a restarted nncg left plateaus its first run stalled on (from the
// written-out warm starts: bed_2d's one unconverged step, 1.24e-5, to 9.1e-6 in 6,209 sweeps;
// 3 of 8 piston_cylinder steps at 1.0-1.7e-5; 2 of 13 piston_2d steps).

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include "mechanics/model/StepInterrupt.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class FallbackContactSolver final : public ContactSolver {
 public:
  // max_unknowns: the second solver is tried only on problems of at most this many body
  // unknowns (6 per sphere, 3 per disk): "ipm" factorises them at every iteration, and above
  // ~3e4 a 3D Cholesky takes seconds (8,765 spheres: about 100 s a fallback step).
  // tolerance: of Siconos' residual (SolverSettings::tolerance); near_miss: see above (0: never
  // once more).
  FallbackContactSolver(std::string name, std::unique_ptr<ContactSolver> first,
                        std::unique_ptr<ContactSolver> second, std::size_t max_unknowns, double tolerance = 0.0,
                        double near_miss = 0.0)
      : name_(std::move(name)), first_(std::move(first)), second_(std::move(second)), max_unknowns_(max_unknowns),
        tolerance_(tolerance), near_miss_residual_(near_miss * tolerance) {}

  // A near miss still unconverged after the first solver's second run gets runs of `sweeps`
  // (plain symmetric Gauss-Seidel sweeps: "nlgs" with a sweep test of 0 and a budget of a few
  // hundred sweeps, so each run is a fixed number of them) up to `budget` sweeps in all, Siconos' residual checked
  // after each run: it stops within the tolerance, or when four runs in a row have not brought
  // the residual 5% below the last mark. The best reactions seen are kept. Why plain sweeps:
  // on the creeping steps of a pressed bed, nncg's conjugate steps plateau a little above the
  // tolerance, where plain sweeps still descend, slowly (Siconos' NSGS, from nncg's stalled
  // reactions at 1.37e-5 on a step of piston_cylinder, within 1e-5 after 2,600 sweeps).
  void set_polisher(std::unique_ptr<ContactSolver> sweeps, int budget) {
    polisher_ = std::move(sweeps);
    polish_budget_ = budget;
  }

  std::string_view name() const override { return name_; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override {
    const auto first_started = std::chrono::steady_clock::now();
    SolveReport kept = first_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
    const std::size_t unknowns = problem.particle_count * (problem.dimension == 2 ? 3 : 6);
    if (kept.converged || problem.compliant || unknowns > max_unknowns_ || !hand_on_) return kept;
    if (step_interrupt_requested()) return kept;  // the step is given up (StepInterrupt.h)
    ++fallbacks_;
    // The later stages' work, reported (SolveReport::fallback_stage): what the default solver's
    // fallback costs, and which stage converges the solves, is for the run to tell.
    const auto started = std::chrono::steady_clock::now();
    const int first_sweeps = kept.sweeps;
    const double q_norm = free_velocity_norm(problem);
    double kept_residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    // Within the tolerance already by Siconos' measure (the first's own stop test unmet): the
    // second solver ("ipm") takes them as they are, at no iteration.
    const bool within = kept_residual <= tolerance_;
    const auto ended_by = [&](int stage) {
      kept.fallback_stage = within ? SolveReport::kWithinWhenHandedOn : stage;
      kept.fallback_sweeps = kept.sweeps - first_sweeps;
      kept.fallback_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      kept.fallback_first_sweeps = first_sweeps;
      kept.fallback_first_s = std::chrono::duration<double>(started - first_started).count();
      return kept;
    };
    run_from_kept(*second_, problem, r, m, velocity, angular_velocity, q_norm, kept, kept_residual);
    if (kept.converged || !(kept_residual <= near_miss_residual_)) return ended_by(SolveReport::kSecondSolver);
    ++near_misses_;
    run_from_kept(*first_, problem, r, m, velocity, angular_velocity, q_norm, kept, kept_residual);
    // Still a near miss: run_from_kept never raises kept_residual. Within the tolerance of
    // Siconos' residual already (the sweep test alone unmet), the step counts as converged by
    // that measure, and plain sweeps, which do not lower it monotonically, could only take it
    // out again.
    if (kept.converged || !polisher_ || kept_residual <= tolerance_) return ended_by(SolveReport::kFirstAgain);
    polish(problem, r, m, velocity, angular_velocity, q_norm, kept, kept_residual);
    return ended_by(SolveReport::kPlainSweeps);
  }
  bool has_fallback() const override { return true; }
  void set_hand_on(bool allowed) override { hand_on_ = allowed; }
  std::vector<double> carried_state() const override { return first_->carried_state(); }
  void restore_carried_state(const std::vector<double>& state) override { first_->restore_carried_state(state); }

  long fallbacks() const { return fallbacks_; }  // solves handed to the second solver so far
  long near_misses() const { return near_misses_; }  // solves given to the first once more
  long polished() const { return polished_; }        // near misses given the plain sweeps

 private:
  // `solver` from the reactions in r, the result so far (`kept`, Siconos' residual
  // `kept_residual`): its result replaces them when it converged or ends no further from the
  // law, else the kept ones are put back. The report counts the sweeps of every run so far.
  void run_from_kept(ContactSolver& solver, const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                     std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                     std::vector<Eigen::Vector3d>& angular_velocity, double q_norm, SolveReport& kept,
                     double& kept_residual) {
    r_ = r;
    m_ = m;
    SolveReport next = solver.solve_with_rolling(problem, r, m, velocity, angular_velocity);
    next.sweeps += kept.sweeps;
    const double residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    if (next.converged || residual <= kept_residual) {
      kept = next;
      kept_residual = residual;
      return;
    }
    r = r_;
    m = m_;
    problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    kept.sweeps = next.sweeps;
  }

  // The plain sweeps of set_polisher() from the reactions in r (Siconos' residual kept_residual):
  // on return r holds the best reactions seen (the given ones if none was better), `kept`
  // counts the sweeps and is converged when they are within the tolerance.
  void polish(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m,
              std::vector<Eigen::Vector3d>& velocity, std::vector<Eigen::Vector3d>& angular_velocity,
              double q_norm, SolveReport& kept, double& kept_residual) {
    ++polished_;
    r_ = r;
    m_ = m;
    v_ = velocity;
    w_ = angular_velocity;
    double best = kept_residual, mark = kept_residual;
    int used = 0, without_gain = 0;
    while (used < polish_budget_) {
      const SolveReport run = polisher_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
      used += run.sweeps;
      kept.sweeps += run.sweeps;
      const double e = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
      if (e < best) {
        best = e;
        r_ = r;
        m_ = m;
        v_ = velocity;
        w_ = angular_velocity;
      }
      if (e <= tolerance_) break;
      if (e < 0.95 * mark) {
        mark = e;
        without_gain = 0;
      } else if (++without_gain >= 4) {
        break;
      }
      if (run.sweeps == 0) break;
    }
    // The best seen (the reactions given when none was better), with their velocities, bit for bit.
    r = r_;
    m = m_;
    velocity = v_;
    angular_velocity = w_;
    if (!(best < kept_residual)) return;
    kept_residual = best;
    kept.residual = best;
    kept.converged = best <= tolerance_;
    kept.stalled = !kept.converged;
  }

  std::string name_;
  std::unique_ptr<ContactSolver> first_, second_, polisher_;
  std::size_t max_unknowns_;
  double tolerance_ = 0.0;
  int polish_budget_ = 0;
  double near_miss_residual_;
  std::vector<Eigen::Vector3d> r_, m_;  // the result kept while another solver runs
  std::vector<Eigen::Vector3d> v_, w_;  // polish(): the best velocities seen
  long fallbacks_ = 0, near_misses_ = 0, polished_ = 0;
  bool hand_on_ = true;  // set_hand_on()
};

}  // namespace tmdem::mechanics

