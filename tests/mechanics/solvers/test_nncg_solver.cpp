// Nonsmooth nonlinear conjugate gradient ("nncg", NncgSolver.h): the closed-form statics of
// heavy-on-light columns and of a frictional lattice pile in fewer sweeps than "nlgs", the same
// fixed points as "nlgs" on a settled frictional pile, only a sweep's reactions ever returned
// (never an extrapolated point), a pile at rest stays at rest; its own stall patience and the
// whole steps of a drift on steps of the examples written out (tests/mechanics/data), and a
// problem without a solution never reported converged.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/ColumnStatics.h"
#include "mechanics/ContactProblemFile.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SameBits.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/solvers/NncgSolver.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// Both solvers cold on a column's problem at 1e-8; both answers checked against the statics
// to the error a Gauss-Seidel stop test leaves, tolerance / (1 - rho) with rho the contraction
// per sweep of "nlgs" (the last sweep of either is a Gauss-Seidel sweep); rho <= 0: the
// contraction "nlgs" shows, tolerance^(1 / sweeps). Returns {nlgs sweeps, nncg sweeps}.
std::pair<int, int> column_sweeps(const std::vector<double>& masses_kg, double rho) {
  constexpr double tolerance = 1e-8;
  const NscdIntegrator sim = column(masses_kg);
  const Solved plain = solve_cold(sim.problem(), "nlgs", tolerance);
  if (rho <= 0.0) rho = std::pow(tolerance, 1.0 / plain.report.sweeps);
  NncgSolver nncg(tight(tolerance));
  const Solved conjugate = solve_cold(sim.problem(), nncg);
  for (const Solved* s : {&plain, &conjugate}) {
    SCOPED_TRACE(s == &plain ? "nlgs" : "nncg");
    EXPECT_TRUE(s->report.converged) << s->report.residual;
    expect_column_statics(sim, s->r, 2.0 * tolerance / (1.0 - rho));
  }
  EXPECT_GT(nncg.steps(), 0);  // the conjugate steps were taken
  return {plain.report.sweeps, conjugate.report.sweeps};
}

// The largest amount by which a reaction leaves its Coulomb cone (r_n < 0 or |r_t| > mu r_n), N s.
double cone_excess(const ContactProblem& p, const std::vector<Vector3d>& r) {
  double excess = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c)
    excess = std::max({excess, -r[c][0], r[c].tail<2>().norm() - p.mu[c] * r[c][0]});
  return excess;
}

// A contact problem of an example run (tests/mechanics/data; ContactProblemFile.h).
ContactProblemFile example_problem(const std::string& name) {
  return read_contact_problem(std::string(TMDEM_SOURCE_DIR) + "/tests/mechanics/data/" + name);
}

// Solves f from its warm start as the run did (its tolerance, stall_sweeps 500).
Solved solve_warm(const ContactProblemFile& f, int max_iterations, const NncgSolver::Options& options) {
  SolverSettings settings;
  settings.tolerance = f.tolerance;
  settings.max_iterations = max_iterations;
  NncgSolver solver(settings, options);
  Solved out;
  out.r = f.r;
  out.report = solver.solve(f.problem, out.r, out.v, out.w);
  return out;
}

// An answer of the run's tolerance: the natural-map residual (scale-free, an independent
// measure: the Jacobi form of the sweeps' change over total) at most twice the tolerance, every
// reaction inside its cone to round-off.
void expect_solved(const ContactProblemFile& f, const Solved& s) {
  double largest = 0.0;
  for (const Vector3d& r : s.r) largest = std::max(largest, r.norm());
  ASSERT_GT(largest, 0.0);
  EXPECT_LE(natural_map_residual(f.problem, s.r, s.v, s.w), 2.0 * f.tolerance);
  EXPECT_LE(cone_excess(f.problem, s.r), 1e-12 * largest);
}

}  // namespace

// 0.5 mm glass under 1 mm steel (mass ratio 25, as in examples/pour_3d.toml), then light-heavy-
// light, then five such pairs stacked: "nlgs" crawls at rho = sqrt(b / (a + b)) = 0.981 per
// sweep (BlockGaussSeidel.HeavyOnLightColumnIsExactInTwoSweeps; 739, 766 and 7,442 sweeps to
// 1e-8, measured), "nncg" follows the slow mode (141, 144 and 456, measured): at most a quarter
// of the sweeps, a tenth on the tall column.
TEST(Nncg, HeavyOnLightColumnsCarryTheirWeightsInFewerSweeps) {
  const double light = sphere_mass(kRadius, kDensity), heavy = 25.0 * light;
  const double rho = plain_contraction(light, heavy);
  const auto two = column_sweeps({light, heavy}, rho);
  EXPECT_GT(two.first, 0.7 * std::log(1e-8) / std::log(rho));  // "nlgs" at its contraction law
  EXPECT_LE(two.second, two.first / 4);
  const auto three = column_sweeps({light, heavy, light}, rho);
  EXPECT_LE(three.second, three.first / 4);
  std::vector<double> tall;
  for (int k = 0; k < 5; ++k) tall.insert(tall.end(), {light, heavy});
  // Five loaded light spheres: the slowest mode contracts more slowly than one pair's rho
  // (0.9975 per sweep, measured).
  const auto ten = column_sweeps(tall, 0.0);
  EXPECT_LE(ten.second, ten.first / 10);
}

// The frictional 5 x 5 x 6 lattice pile: the closed-form statics and "nlgs"'s reactions (to
// 1e-6 of the weights), the natural-map residual of the tolerance, in fewer sweeps (cold to
// 1e-8: "nlgs" 279, "nncg" 82, measured).
TEST(Nncg, FrictionalLatticePileMatchesGaussSeidelAndStatics) {
  constexpr double tolerance = 1e-8;
  expect_pile_solved_like_gauss_seidel("nncg", tolerance, 2.0 * tolerance);
  const ContactProblem& problem = lattice_pile().problem();
  const Solved plain = solve_cold(problem, "nlgs", tolerance);
  const Solved conjugate = solve_cold(problem, "nncg", tolerance);
  EXPECT_LE(conjugate.report.sweeps, plain.report.sweeps / 2);
}

// The settled 2D pile of the rest tests (mu = 0.5; a frictional pile's reactions are not
// unique, so the answers are compared by their fixed points): cold, "nncg" reaches the
// natural-map residual of the tolerance with the floor carrying the weight, and each solver
// started from the other's answer stops within two sweeps without moving it beyond what the
// tolerance allows. Those answers are taken at 1e-13: at 1e-8 a Gauss-Seidel stop test leaves
// an error in the slow mode, tolerance / (1 - contraction), that the other solver then removes.
TEST(Nncg, SettledFrictionalPileHasTheFixedPointsOfGaussSeidel) {
  NscdIntegrator sim = settled_disk_pile();
  ASSERT_LT(sim.max_speed(), 1e-9);
  sim.step();
  const ContactProblem& problem = sim.problem();
  constexpr double tolerance = 1e-8;
  const Solved conjugate = solve_cold(problem, "nncg", tolerance);
  const Solved plain = solve_cold(problem, "nlgs", 1e-13);
  const Solved conjugate_tight = solve_cold(problem, "nncg", 1e-13);
  ASSERT_TRUE(conjugate.report.converged) << conjugate.report.residual;
  ASSERT_TRUE(plain.report.converged);
  ASSERT_TRUE(conjugate_tight.report.converged);
  EXPECT_LE(natural_map_residual(problem, conjugate.r, conjugate.v, conjugate.w), 2.0 * tolerance);
  double weight_Ns = 0.0, floor_Ns = 0.0, largest = 0.0;
  for (double m : sim.particles().mass) weight_Ns += m * kG * sim.parameters().time_step;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (problem.body_j[c] == wall_code<std::int32_t>(0)) floor_Ns += global_impulse(problem, c, conjugate.r[c]).y();
    largest = std::max(largest, plain.r[c].norm());
  }
  EXPECT_NEAR(floor_Ns, weight_Ns, 1e-5 * weight_Ns);
  EXPECT_LE(cone_excess(problem, conjugate.r), 1e-12 * weight_Ns);
  for (const bool nncg_from_nlgs : {true, false}) {
    SCOPED_TRACE(nncg_from_nlgs ? "nncg from nlgs" : "nlgs from nncg");
    const std::vector<Vector3d>& start = nncg_from_nlgs ? plain.r : conjugate_tight.r;
    std::vector<Vector3d> r = start, v, w;
    const SolveReport report =
        make_contact_solver(nncg_from_nlgs ? "nncg" : "nlgs", tight(tolerance))->solve(problem, r, v, w);
    EXPECT_TRUE(report.converged);
    EXPECT_LE(report.sweeps, 2);
    EXPECT_LE(largest_difference(r, start), 10.0 * tolerance * largest);
  }
}

// Stopped by max_iterations after a backward sweep (where a conjugate step would come next) or
// after a forward one, far from converged: the reactions are those of the last sweep, each
// inside its cone, and the velocities returned are exactly v_free + M^-1 H r of them (the
// conjugate steps moved the velocities with the reactions).
TEST(Nncg, StoppedEarlyItReturnsASweepsReactions) {
  const ContactProblem& problem = lattice_pile().problem();
  for (const int sweeps : {6, 7, 8}) {
    SCOPED_TRACE(sweeps);
    SolverSettings settings;
    settings.tolerance = 1e-12;
    settings.max_iterations = sweeps;
    NncgSolver solver(settings);
    const Solved s = solve_cold(problem, solver);
    ASSERT_FALSE(s.report.converged);
    ASSERT_EQ(s.report.sweeps, sweeps);
    EXPECT_GT(solver.steps(), 0);  // extrapolated on the way
    EXPECT_LE(cone_excess(problem, s.r), 0.0);
    std::vector<Vector3d> v, w;
    problem.velocities_from_reactions(s.r, v, w);
    double difference = 0.0, scale = 0.0;
    for (std::size_t b = 0; b < v.size(); ++b) {
      difference = std::max({difference, (v[b] - s.v[b]).norm(), (w[b] - s.w[b]).norm()});
      scale = std::max(scale, problem.free_velocity[b].norm());
    }
    EXPECT_LE(difference, 1e-12 * scale);
  }
}

// With rolling resistance (the rolling impulses are extrapolated with the reactions): a 3D pile
// (radii 1 and 0.7 mm, mu = 0.5, mu_r = 0.1) settled with "nlgs", its last problem solved cold:
// the natural-map residual with the rolling blocks counted, both cones held, the pile left at
// rest as "nlgs" leaves it (BlockGaussSeidel.RollingPileLikeGaussSeidel).
TEST(Nncg, RollingPileLikeGaussSeidel) {
  const NscdIntegrator sim = settled_rolling_pile();
  NncgSolver nncg(tight(1e-7));
  expect_rolling_pile_solved(sim, nncg, 1e-7);
  EXPECT_GT(nncg.steps(), 0);
}

// At rest means at rest with "nncg" too: the pile of NscdRest.RestingPileStaysAtRestFor10000Steps
// (settled with "nlgs"), carried on with "nncg" (a new integrator: its first steps start cold,
// so 200 steps first), moves less than 1e-9 m and stays below 1e-8 m/s for 10,000 steps.
TEST(Nncg, RestingPileStaysAtRestFor10000Steps) {
  std::unique_ptr<NscdIntegrator> sim;
  const Drift drift = drift_at_rest_with("nncg", sim);
  EXPECT_LT(drift.fastest_m_per_s, 1e-8);
  EXPECT_LT(drift.moved_m, 1e-9);
}

// A settle step of column_in_air (144 contacts, tolerance 1e-6) on which the residual of "nncg"
// stays within 10% of its best for more than 500 sweeps and then falls: the shared stall rule
// of "nlgs" (patience 1) gives up in the plateau, unconverged; "nncg"'s own patience (10% over
// 8 x 500 sweeps) carries it to the tolerance (measured: stalled after 624 sweeps at 1.6e-6;
// converged after 2,582).
TEST(Nncg, ColumnInAirPlateauConvergesWithItsOwnPatience) {
  const ContactProblemFile f = example_problem("nncg_plateau_column_in_air.txt");
  NncgSolver::Options shared;
  shared.stall_patience = 1;
  shared.stall_restarts = 0;
  const Solved stopped = solve_warm(f, 10000, shared);
  EXPECT_TRUE(stopped.report.stalled);
  EXPECT_FALSE(stopped.report.converged);
  EXPECT_GT(stopped.report.residual, f.tolerance);
  const Solved solved = solve_warm(f, 10000, NncgSolver::Options{});
  ASSERT_TRUE(solved.report.converged) << solved.report.residual << " after " << solved.report.sweeps;
  EXPECT_GT(solved.report.sweeps, stopped.report.sweeps + 500);  // through the plateau
  expect_solved(f, solved);
  // Restarted after its stalls (Options::stall_restarts) until the budget runs out, the solve
  // still returns a sweep's reactions, never a conjugate step's extrapolation: every one in
  // its cone, for budgets ending on a forward and on a backward sweep.
  shared.stall_restarts = 3;
  for (const int budget : {1500, 1501}) {
    const Solved restarted = solve_warm(f, budget, shared);
    if (restarted.report.converged) continue;
    EXPECT_EQ(restarted.report.sweeps, budget);
    double largest = 0.0;
    for (const Vector3d& r : restarted.r) largest = std::max(largest, r.norm());
    EXPECT_LE(cone_excess(f.problem, restarted.r), 1e-12 * largest) << budget;
  }
}

// A settle step of the 2D bed_in_air (99 contacts, tolerance 1e-6): the pairs' change stays the
// same for hundreds of sweeps (|d_k+1|^2 / |d_k|^2 = 1.0000-1.006). With beta = 1 there (a
// drift) it converges; with those pairs damped to 0.7 (drift_ratio 1) the same number of sweeps
// leaves it at 16x the tolerance, and it needs twice as many (measured: 1,998 and 4,200).
TEST(Nncg, BedInAirDriftConvergesWithWholeSteps) {
  const ContactProblemFile f = example_problem("nncg_drift_bed_in_air.txt");
  ASSERT_EQ(f.problem.dimension, 2);
  SolverSettings settings;
  settings.tolerance = f.tolerance;
  NncgSolver solver(settings);
  Solved solved;
  solved.r = f.r;
  solved.report = solver.solve(f.problem, solved.r, solved.v, solved.w);
  ASSERT_TRUE(solved.report.converged) << solved.report.residual;
  EXPECT_GT(solver.drifted(), 0);
  expect_solved(f, solved);
  NncgSolver::Options damped;
  damped.drift_ratio = 1.0;
  const Solved same_sweeps = solve_warm(f, solved.report.sweeps, damped);
  EXPECT_FALSE(same_sweeps.report.converged);
  EXPECT_GT(same_sweeps.report.residual, 10.0 * f.tolerance);
  const Solved slow = solve_warm(f, 10000, damped);
  ASSERT_TRUE(slow.report.converged) << slow.report.residual;
  EXPECT_GT(slow.report.sweeps, 3 * solved.report.sweeps / 2);
}

// Without a solution: a sphere between two fixed parallel walls, each contact asking it to
// leave its wall at 1 m/s (bias -1 m/s). Gauss-Seidel raises both reactions every sweep and the
// conjugate steps follow (a drift); the residual change / total falls only as 1 / sweeps. Never
// reported converged, whatever the budget: stopped by max_iterations, unconverged, with finite
// reactions. Below the round-off of a real problem (tolerance 1e-17 on the column_in_air step)
// the residual stops falling and the solve is reported stalled, before max_iterations.
TEST(Nncg, ProblemWithoutSolutionIsNeverReportedConverged) {
  ContactProblem p;
  p.inverse_mass = {1.0 / sphere_mass(kRadius, kDensity)};
  p.inverse_inertia = {1.0};
  p.free_velocity = {Vector3d::Zero()};
  p.free_angular_velocity = {Vector3d::Zero()};
  p.add_fixed_wall_bodies(2);
  p.resize_contacts(2);
  for (int k = 0; k < 2; ++k) {
    const double side = k == 0 ? 1.0 : -1.0;
    p.body_i[k] = 0;
    p.body_j[k] = wall_code<std::int32_t>(k);
    p.normal[k] = Vector3d(0, side, 0);
    p.tangent1[k] = Vector3d(side, 0, 0);
    p.tangent2[k] = Vector3d(0, 0, 1);
    p.lever_i[k] = kRadius;
    p.lever_j[k] = 0.0;
    p.w_n[k] = p.inverse_mass[0];
    p.w_t[k] = p.inverse_mass[0] + kRadius * kRadius * p.inverse_inertia[0];
    p.bias[k] = -1.0;
    p.mu[k] = 0.3;
  }
  for (const int budget : {100, 2000}) {
    SCOPED_TRACE(budget);
    SolverSettings settings = tight(1e-6);
    settings.max_iterations = budget;
    NncgSolver solver(settings);
    const Solved s = solve_cold(p, solver);
    EXPECT_FALSE(s.report.converged);
    EXPECT_EQ(s.report.sweeps, budget);
    EXPECT_GT(s.report.residual, 1e-6);
    EXPECT_TRUE(std::isfinite(s.r[0][0]) && std::isfinite(s.r[1][0]));
  }
  ContactProblemFile f = example_problem("nncg_plateau_column_in_air.txt");
  f.tolerance = 1e-17;
  const Solved floor = solve_warm(f, 200000, NncgSolver::Options{});
  EXPECT_TRUE(floor.report.stalled);
  EXPECT_FALSE(floor.report.converged);
  EXPECT_LT(floor.report.sweeps, 200000);
}

namespace tmdem::mechanics {
namespace {

// "nncg_coloured": the conjugate steps on coloured sweeps. The lattice pile's statics and
// "nlgs"'s reactions, in fewer sweeps than coloured Gauss-Seidel alone; and the same bits at 1
// and 2 threads (the colours are OpenMP loops from parallel_from contacts; 0 here).
TEST(NncgColoured, FrictionalLatticePileMatchesGaussSeidelAndStatics) {
  constexpr double tolerance = 1e-8;
  test::expect_pile_solved_like_gauss_seidel("nncg_coloured", tolerance, 10.0 * tolerance);
  const ContactProblem& problem = test::lattice_pile().problem();
  const test::Solved plain = test::solve_cold(problem, "nlgs_coloured", tolerance);
  const test::Solved conjugate = test::solve_cold(problem, "nncg_coloured", tolerance);
  EXPECT_LE(conjugate.report.sweeps, plain.report.sweeps / 2)
      << plain.report.sweeps << " against " << conjugate.report.sweeps;
}

TEST(NncgColoured, SameBitsForAnyThreadCount) {
  const ContactProblem& problem = test::lattice_pile().problem();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    SolverSettings settings = test::tight(1e-12);
    settings.max_iterations = 60;
    NncgSolver::Options options;
    options.coloured = true;
    settings.parallel_from = 0;
    NncgSolver solver(settings, options);
    return test::solve_cold(problem, solver);
  };
  const int threads_before = omp_get_max_threads();
  const test::Solved first = run(2), second = run(2), serial = run(1);
  omp_set_num_threads(threads_before);
  EXPECT_EQ(first.report.sweeps, 60);
  EXPECT_TRUE(test::same_bits(first.r, second.r));
  EXPECT_TRUE(test::same_bits(first.r, serial.r));
  EXPECT_TRUE(test::same_bits(first.v, serial.v));
  EXPECT_TRUE(test::same_bits(first.w, serial.w));
}

}  // namespace
}  // namespace tmdem::mechanics
