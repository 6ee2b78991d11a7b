// Active-set sweeps of the Gauss-Seidel solvers (ActiveContactSet.h): sweeps that visit the
// active contacts only give the answer of sweeps over every candidate, and a candidate that
// was open when last visited but closes later in the solve is caught by a full sweep.
#include <gtest/gtest.h>

#include <string>

#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/ColouredGaussSeidelSolver.h"
#include "mechanics/solvers/GaussSeidelSolver.h"
#include "mechanics/contact/NaturalMapResidual.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

std::unique_ptr<ContactSolver> gauss_seidel(const std::string& name, double tolerance,
                                            int full_sweep_every, int max_sweeps = 200000) {
  SolverSettings settings = tight(tolerance);
  settings.full_sweep_every = full_sweep_every;
  settings.max_iterations = max_sweeps;
  // "nlgs_coloured" on one thread at these sizes (parallel_from); its thread counts are
  // test_coloured_gauss_seidel.cpp's.
  if (name == "nlgs_coloured") return std::make_unique<ColouredGaussSeidelSolver>(settings);
  return std::make_unique<GaussSeidelSolver>(settings);
}

// Sphere B falls onto sphere A, which rests on the floor; both fall at g h before the
// contacts act. Contact 0 (B on A, normal up from A to B) has a gap that B closes within the
// step (bias = gap / h < g h); contact 1 is A on the floor. Visited in index order, contact 0
// is open on its first visit (A and B fall together: u_n = bias > 0), so it is passive; then
// contact 1 stops A, and only a later visit of contact 0 sees B approaching A.
// Exact answer (both contacts closed, u_n = 0): v_A = 0, v_B,y = -bias,
// r_0 = m_B (g h - bias), r_1 = m_A g h + r_0.
struct FallingOntoResting {
  ContactProblem problem;
  double r0 = 0.0, r1 = 0.0, bias = 0.0;
};

FallingOntoResting falling_onto_resting() {
  const double m_a = 2.0, m_b = 3.0, h = 1e-3, radius = 1e-3;
  FallingOntoResting s;
  s.bias = 0.25 * kG * h;  // B closes its gap within the step
  ContactProblem& p = s.problem;
  p.dimension = 3;
  p.inverse_mass = {1.0 / m_a, 1.0 / m_b};
  const double inertia = 0.4 * radius * radius;
  p.inverse_inertia = {1.0 / (m_a * inertia), 1.0 / (m_b * inertia)};
  p.free_velocity = {Vector3d(0, -kG * h, 0), Vector3d(0, -kG * h, 0)};
  p.free_angular_velocity = {Vector3d::Zero(), Vector3d::Zero()};
  p.resize_contacts(2);
  p.body_i = {1, 0};  // contact 0: B (i) on A (j); contact 1: A on the floor (wall 0)
  p.body_j = {0, -1};
  p.normal = {Vector3d(0, 1, 0), Vector3d(0, 1, 0)};
  p.tangent1 = {Vector3d(1, 0, 0), Vector3d(1, 0, 0)};
  p.tangent2 = {Vector3d(0, 0, -1), Vector3d(0, 0, -1)};
  p.lever_i = {radius, radius};
  p.lever_j = {radius, 0.0};
  // Central contacts: w_t = 1/m + R^2/I per body (t x n lever terms), w_n = 1/m per body.
  p.w_n = {1.0 / m_a + 1.0 / m_b, 1.0 / m_a};
  p.w_t = {1.0 / m_a + 1.0 / m_b + 2.5 / m_a + 2.5 / m_b, 1.0 / m_a + 2.5 / m_a};
  p.bias = {s.bias, 0.0};
  p.mu = {0.3, 0.3};
  p.add_fixed_wall_bodies(1);
  s.r0 = m_b * (kG * h - s.bias);
  s.r1 = m_a * kG * h + s.r0;
  return s;
}

}  // namespace

class ActiveSetSweeps : public ::testing::TestWithParam<std::string> {};

// Whatever the period of full sweeps (1: every sweep; 1000: only the full sweep that must
// confirm convergence), the closing candidate is found and the answer is the exact one.
TEST_P(ActiveSetSweeps, APassiveCandidateThatClosesIsCaught) {
  const FallingOntoResting s = falling_onto_resting();
  for (const int every : {1, 3, 1000}) {
    SCOPED_TRACE(every);
    auto solver = gauss_seidel(GetParam(), 1e-13, every);
    std::vector<Vector3d> r(2, Vector3d::Zero()), v, w;
    const SolveReport report = solver->solve(s.problem, r, v, w);
    ASSERT_TRUE(report.converged) << report.residual;
    const double scale = s.r1;
    EXPECT_NEAR(r[0][0], s.r0, 1e-12 * scale);
    EXPECT_NEAR(r[1][0], s.r1, 1e-12 * scale);
    EXPECT_NEAR(r[0].tail<2>().norm() + r[1].tail<2>().norm(), 0.0, 1e-12 * scale);
    EXPECT_NEAR(v[0].norm(), 0.0, 1e-12 * kG * 1e-3);
    EXPECT_NEAR(v[1].y(), -s.bias, 1e-12 * kG * 1e-3);
    // Sweep 1 (full) leaves contact 0 open; a later sweep catches it, so at least one sweep
    // after the first changed something, and the last sweep was full (convergence).
    EXPECT_GE(report.sweeps, 3);
  }
}

// A collapsing frictionless pile: look-ahead candidates far outnumber the contacts, and
// during a cold solve contacts close and open again. Frictionless, the velocities that
// solve the problem are unique (a strictly convex quadratic program), so sweeps over active
// sets must reach those of sweeps over every candidate, to the tolerance.
TEST_P(ActiveSetSweeps, SameAnswerAsFullSweepsOnACollapsingPile) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-4;
  parameters.max_iterations = 300;
  NscdIntegrator sim = random_pile(150, 3, 0.0, 3, parameters);
  for (int step = 0; step < 40; ++step) sim.step();
  const ContactProblem& problem = sim.problem();
  ASSERT_GT(problem.size(), 2 * sim.contacts().size()) << "candidates should outnumber contacts";

  const double tolerance = 1e-10;
  auto solve = [&](int every, int max_sweeps) {
    return solve_cold(problem, *gauss_seidel(GetParam(), tolerance, every, max_sweeps));
  };
  // Contacts open and close during the solve: some closed after the first sweep are open at
  // the end, and some open after the first sweep are closed at the end.
  const Solved first = solve(1, 1);
  const Solved full = solve(1, 200000);
  ASSERT_TRUE(full.report.converged) << full.report.residual;
  int closed_then_open = 0, open_then_closed = 0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    const bool closed_first = first.r[c][0] > 0.0, closed_end = full.r[c][0] > 0.0;
    closed_then_open += closed_first && !closed_end ? 1 : 0;
    open_then_closed += !closed_first && closed_end ? 1 : 0;
  }
  EXPECT_GT(closed_then_open, 0);
  EXPECT_GT(open_then_closed, 0);

  double speed = 0.0;
  for (const Vector3d& v : full.v) speed = std::max(speed, v.norm());
  ASSERT_GT(speed, 0.0);
  for (const int every : {2, 8, 32}) {
    SCOPED_TRACE(every);
    const Solved active = solve(every, 200000);
    ASSERT_TRUE(active.report.converged) << active.report.residual;
    EXPECT_LE(natural_map_residual(problem, active.r, active.v, active.w), 10 * tolerance);
    EXPECT_LE(largest_difference(full.v, active.v), 1e-6 * speed);
    expect_close_reactions(full.r, active.r, 1e-6);
  }
}

namespace {

// An integrator that continues `sim` (its state: positions, velocities, candidates, warm
// start) with another full-sweep period for the solver `solver`.
NscdIntegrator continued_with(const NscdIntegrator& sim, const std::string& solver,
                              int full_sweep_every) {
  NscdParameters parameters = sim.parameters();
  parameters.solver = solver;
  parameters.full_sweep_every = full_sweep_every;
  NscdIntegrator next(sim.particles(), sim.materials(), sim.walls(), sim.gravity(),
                      sim.dimension(), parameters);
  next.restore_state(sim.save_state());
  return next;
}

}  // namespace

// The pile of test_nscd_rest.cpp, settled with full sweeps only (every speed below 1e-9 m/s,
// solver tolerance 1e-8), then stepped on with active-set sweeps: a state at rest is a fixed
// point of the active-set solve as it is of the plain one, so the pile stays put, with the
// rest test's bounds (no speed above 1e-8 m/s, no particle moving by 1e-9 m in 2 s).
TEST_P(ActiveSetSweeps, ARestingPileStaysAtRest) {
  const NscdIntegrator settled = settled_disk_pile(1, 1);
  ASSERT_LT(settled.max_speed(), 1e-9) << "the pile did not settle";
  for (const int every : {8, 32}) {
    SCOPED_TRACE(every);
    NscdIntegrator sim = continued_with(settled, GetParam(), every);
    const std::int64_t unconverged_before = sim.stats().unconverged_steps;  // while settling
    const Drift drift = drift_over(sim, 2000);
    EXPECT_LT(drift.fastest_m_per_s, 1e-8);
    EXPECT_LT(drift.moved_m, 1e-9);
    EXPECT_EQ(sim.stats().unconverged_steps, unconverged_before);
  }
}

INSTANTIATE_TEST_SUITE_P(GaussSeidel, ActiveSetSweeps, ::testing::Values("nlgs", "nlgs_coloured"));
