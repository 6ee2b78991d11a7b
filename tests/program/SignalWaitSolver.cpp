// A testing aid, not physics, registered only by the test program tmdem_testing (never by
// tmdem): a contact solver whose solves do not end until the step in progress is given up
// (mechanics/model/StepInterrupt.h), so that a test can signal a run while a step is being
// solved, as a user's Ctrl-C comes during a solve of minutes. A scene asks for it by name:
//   [mechanics] solver = "wait_for_signal"
// It leaves the warm start as it is and reports the solve unconverged. A run that never gets
// its signal is not left hanging: a solve ends after two minutes.
#include "SignalWaitSolver.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include "mechanics/model/StepInterrupt.h"

namespace tmdem::testing {
namespace {

using namespace tmdem::mechanics;

class SignalWaitSolver final : public ContactSolver {
 public:
  std::string_view name() const override { return "wait_for_signal"; }

  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    // The line a test waits for before it signals (the run's own progress comes after steps).
    if (!announced_) std::fputs("wait_for_signal: solving until the step is given up\n", stderr);
    announced_ = true;
    SolveReport report;
    while (!step_interrupt_requested() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      ++report.sweeps;
    }
    problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    report.converged = false;
    report.residual = 1.0;
    return report;
  }

 private:
  bool announced_ = false;
};

}  // namespace

std::unique_ptr<ContactSolver> make_signal_wait_solver(const SolverSettings&) {
  return std::make_unique<SignalWaitSolver>();
}

}  // namespace tmdem::testing
