// A step given up at a request (mechanics/model/StepInterrupt.h; a SIGINT/SIGTERM during a
// run): the solvers stop at their next sweep or iteration, the step leaves the state, the
// counters and the warm start as at its start, and the steps after it are bit for bit those of
// a run that was never interrupted. Unarmed, a request does nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mechanics/ContactProblemFile.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/model/StepInterrupt.h"
#include "mechanics/solvers/ContactSolverRegistry.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace step_interrupt_test {

// Arms and raises a request for the scope of the object; drops it and disarms at the end.
struct RaisedRequest {
  RaisedRequest() {
    arm_step_interrupt(true);
    request_step_interrupt();
  }
  ~RaisedRequest() {
    clear_step_interrupt();
    arm_step_interrupt(false);
  }
};

// reactions: compare reactions() too (after a step; a restored state keeps its warm start apart,
// keyed by pair, until the next step builds its problem).
void expect_same_state(const NscdIntegrator& a, const NscdIntegrator& b, const std::string& when,
                       bool reactions = true) {
  ASSERT_EQ(a.particles().size(), b.particles().size());
  for (std::size_t i = 0; i < a.particles().size(); ++i) {
    ASSERT_EQ(a.particles().position[i], b.particles().position[i]) << when << ", particle " << i;
    ASSERT_EQ(a.particles().velocity[i], b.particles().velocity[i]) << when << ", particle " << i;
    ASSERT_EQ(a.particles().angular_velocity[i], b.particles().angular_velocity[i]) << when << ", particle " << i;
  }
  if (reactions) {
    ASSERT_EQ(a.reactions(), b.reactions()) << when;
  }
  EXPECT_EQ(a.stats().steps, b.stats().steps) << when;
  EXPECT_EQ(a.stats().unconverged_steps, b.stats().unconverged_steps) << when;
  EXPECT_EQ(a.stats().unconverged_time_steps, b.stats().unconverged_time_steps) << when;
}

}  // namespace step_interrupt_test

using namespace step_interrupt_test;

TEST(StepInterrupt, UnarmedRequestDoesNothing) {
  clear_step_interrupt();
  arm_step_interrupt(false);
  request_step_interrupt();
  EXPECT_FALSE(step_interrupt_requested());
  {
    RaisedRequest raised;
    EXPECT_TRUE(step_interrupt_requested());
  }
  EXPECT_FALSE(step_interrupt_requested());
}

// 60 spheres poured into a box, every solver (the default among them): three steps, then one
// given up, then three more, against a twin never interrupted. The step given up mid-fall
// (its solve stopped after a sweep, the positions not yet updated) leaves the twin's state
// exactly; the steps after it are the twin's, bit for bit, warm start included, and so are
// those of its checkpoint restored.
TEST(StepInterrupt, GivenUpStepLeavesTheStartAndTheRunGoesOnAsNeverInterrupted) {
  for (const std::string& solver : contact_solver_names()) {
    SCOPED_TRACE(solver);
    NscdParameters parameters = nlgs_parameters();
    parameters.solver = solver;
    NscdIntegrator a = random_pile(60, 3, 0.4, 5, parameters, 0.02);
    NscdIntegrator b = random_pile(60, 3, 0.4, 5, parameters, 0.02);
    for (int k = 0; k < 30; ++k) {  // into the landing: contacts that carry load
      a.step();
      b.step();
    }
    {
      RaisedRequest raised;
      const StepReport given_up = a.step();
      EXPECT_TRUE(given_up.interrupted);
      EXPECT_FALSE(given_up.converged);
    }
    expect_same_state(a, b, "after the step given up", false);
    // Its checkpoint (what the run writes then) restored into a fresh integrator goes on as well.
    NscdIntegrator c = random_pile(60, 3, 0.4, 5, parameters, 0.02);
    c.restore_state(a.save_state());
    NscdIntegrator d = random_pile(60, 3, 0.4, 5, parameters, 0.02);
    d.restore_state(b.save_state());
    for (int k = 0; k < 3; ++k) {
      c.step();
      d.step();
      expect_same_state(c, d, "restored, step " + std::to_string(k) + " after");
    }
    for (int k = 0; k < 3; ++k) {
      const StepReport ra = a.step(), rb = b.step();
      EXPECT_FALSE(ra.interrupted);
      EXPECT_EQ(ra.sweeps, rb.sweeps) << "step " << k;
      expect_same_state(a, b, "step " + std::to_string(k) + " after");
    }
  }
}

// Every solver stops within two sweeps or iterations of a request, unconverged, on a stored
// settle step that takes "nncg" 2,582 sweeps (tests/mechanics/data).
TEST(StepInterrupt, EverySolverStopsAtOnce) {
  const ContactProblemFile f = read_contact_problem(std::string(TMDEM_SOURCE_DIR) +
                                                    "/tests/mechanics/data/nncg_plateau_column_in_air.txt");
  for (const std::string& name : contact_solver_names()) {
    SCOPED_TRACE(name);
    SolverSettings settings;
    settings.tolerance = f.tolerance;
    settings.max_iterations = 10000;
    auto solver = make_contact_solver(name, settings);
    std::vector<Eigen::Vector3d> r = f.r, m = f.m;
    std::vector<Eigen::Vector3d> v(f.problem.body_count()), w(f.problem.body_count());
    const SolveReport free_run = solver->solve_with_rolling(f.problem, r, m, v, w);
    EXPECT_GT(free_run.sweeps, 10);  // a solve that needs many sweeps
    r = f.r;
    m = f.m;
    RaisedRequest raised;
    const SolveReport stopped = solver->solve_with_rolling(f.problem, r, m, v, w);
    EXPECT_LE(stopped.sweeps, 2);
    EXPECT_FALSE(stopped.converged);
  }
}
