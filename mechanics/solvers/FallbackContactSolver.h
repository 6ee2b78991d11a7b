#pragma once
// A contact solver that hands the steps its first solver does not converge to a second one,
// started from the first one's reactions ("nncg_ipm": nncg, then the interior point). Where the
// first converges, the result is the first's, to the bit: the fallback costs nothing on the
// steps that never needed it. Compliant problems are the first solver's alone (ContactSolverRegistry
// lists "nncg_ipm" as taking them: it is "nncg" there).

#include <memory>
#include <string>

#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class FallbackContactSolver final : public ContactSolver {
 public:
  FallbackContactSolver(std::string name, std::unique_ptr<ContactSolver> first,
                        std::unique_ptr<ContactSolver> second)
      : name_(std::move(name)), first_(std::move(first)), second_(std::move(second)) {}

  std::string_view name() const override { return name_; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override {
    const SolveReport first = first_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
    // A compliant problem (mechanics.normal_law = "hertz") stays with the first solver: the
    // second ("ipm") takes rigid contacts only.
    if (first.converged || problem.compliant) return first;
    ++fallbacks_;
    SolveReport second = second_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
    second.sweeps += first.sweeps;
    return second;
  }
  std::vector<double> carried_state() const override { return first_->carried_state(); }
  void restore_carried_state(const std::vector<double>& state) override { first_->restore_carried_state(state); }

  long fallbacks() const { return fallbacks_; }  // solves handed to the second solver so far

 private:
  std::string name_;
  std::unique_ptr<ContactSolver> first_, second_;
  long fallbacks_ = 0;
};

}  // namespace tmdem::mechanics
