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

#include <cstddef>
#include <memory>
#include <string>

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
        near_miss_residual_(near_miss * tolerance) {}

  std::string_view name() const override { return name_; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override {
    SolveReport kept = first_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
    const std::size_t unknowns = problem.particle_count * (problem.dimension == 2 ? 3 : 6);
    if (kept.converged || problem.compliant || unknowns > max_unknowns_) return kept;
    ++fallbacks_;
    const double q_norm = free_velocity_norm(problem);
    double kept_residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    run_from_kept(*second_, problem, r, m, velocity, angular_velocity, q_norm, kept, kept_residual);
    if (kept.converged || !(kept_residual <= near_miss_residual_)) return kept;
    ++near_misses_;
    run_from_kept(*first_, problem, r, m, velocity, angular_velocity, q_norm, kept, kept_residual);
    return kept;
  }
  std::vector<double> carried_state() const override { return first_->carried_state(); }
  void restore_carried_state(const std::vector<double>& state) override { first_->restore_carried_state(state); }

  long fallbacks() const { return fallbacks_; }  // solves handed to the second solver so far
  long near_misses() const { return near_misses_; }  // solves given to the first once more

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

  std::string name_;
  std::unique_ptr<ContactSolver> first_, second_;
  std::size_t max_unknowns_;
  double near_miss_residual_;
  std::vector<Eigen::Vector3d> r_, m_;  // the result kept while another solver runs
  long fallbacks_ = 0, near_misses_ = 0;
};

}  // namespace tmdem::mechanics
