// Gauss-Seidel with subspace minimisation on the active set ("nlgs_subspace",
// SubspaceGaussSeidelSolver.h; "nncg_subspace", NncgSolver.h; the step: ActiveSetSubspaceStep.h): the closed-form statics of uniform and heavy-on-light columns in
// a number of sweeps that does not grow with the height, the frictional lattice pile like
// "nlgs", random problems (every branch: open, stick, slip, walls, a piston, rolling) and the
// stored problems of the examples to the natural-map residual of their tolerance, and the same
// total normal impulse as "nncg" on a settled frictional pile.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mechanics/ColumnStatics.h"
#include "mechanics/ContactProblemFile.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/RandomContactProblem.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/solvers/SubspaceGaussSeidelSolver.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// The largest amount by which a reaction leaves its Coulomb cone, N s.
double cone_overshoot(const ContactProblem& p, const std::vector<Vector3d>& r) {
  double excess = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c)
    excess = std::max({excess, -r[c][0], r[c].tail<2>().norm() - p.mu[c] * r[c][0]});
  return excess;
}

// A column's problem solved cold at `tolerance`: converged, the statics to a few tolerances of
// the largest load (the last sweep is a Gauss-Seidel sweep, started next to the exact answer),
// the subspace steps taken; returns the sweeps.
int column_solved(const std::vector<double>& masses_kg, double tolerance) {
  const NscdIntegrator sim = test::column(masses_kg);
  SubspaceGaussSeidelSolver solver(test::tight(tolerance));
  const Solved s = solve_cold(sim.problem(), solver);
  EXPECT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
  test::expect_column_statics(sim, s.r, 10.0 * tolerance);
  EXPECT_GT(solver.subspace().accepted(), 0);
  // "nncg_subspace": the same steps kept, so the same statics.
  const Solved conjugate = solve_cold(sim.problem(), "nncg_subspace", tolerance);
  EXPECT_TRUE(conjugate.report.converged) << conjugate.report.residual;
  test::expect_column_statics(sim, conjugate.r, 10.0 * tolerance);
  EXPECT_LE(conjugate.report.sweeps, s.report.sweeps + 2);
  return s.report.sweeps;
}

ContactProblemFile stored_problem(const std::string& name) {
  return read_contact_problem(std::string(TMDEM_SOURCE_DIR) + "/tests/mechanics/data/" + name);
}

}  // namespace

TEST(SubspaceGaussSeidel, IsRegisteredByName) {
  EXPECT_EQ(make_contact_solver("nlgs_subspace", {})->name(), "nlgs_subspace");
  EXPECT_EQ(make_contact_solver("nncg_subspace", {})->name(), "nncg_subspace");
}

// Uniform columns of 10, 40 and 160 spheres: "nlgs" needs sweeps growing with the height
// (a chain's slowest mode: 667, 7,957 and stalled at 7,286; "nncg" 134, 472, 1,491, measured),
// the subspace step solves the closed chain at once (3 sweeps at every height, measured; from
// cold a sweep pair carries the load up only about 42 contacts before the velocity increments
// fall below round-off, and the resting contacts above join the active set all the same).
// Issue 24's target, at most 2x the sweeps for 16x the height, asserted, and a tenth of
// "nlgs"'s at 40.
TEST(SubspaceGaussSeidel, UniformColumnsTakeSweepsIndependentOfHeight) {
  constexpr double tolerance = 1e-8;
  const double m = sphere_mass(kRadius, kDensity);
  std::vector<int> sweeps;
  for (const int layers : {10, 40, 160}) {
    SCOPED_TRACE(layers);
    sweeps.push_back(column_solved(std::vector<double>(static_cast<std::size_t>(layers), m), tolerance));
  }
  EXPECT_LE(sweeps[1], 2 * sweeps[0]) << sweeps[0] << ", " << sweeps[1];
  EXPECT_LE(sweeps[2], 2 * sweeps[0]) << sweeps[0] << ", " << sweeps[1] << ", " << sweeps[2];
  const NscdIntegrator tall = test::column(std::vector<double>(40, m));
  const Solved plain = solve_cold(tall.problem(), "nlgs", tolerance);
  EXPECT_GE(plain.report.sweeps, 10 * sweeps[1]) << plain.report.sweeps << " against " << sweeps[1];
}

// Heavy on light (mass ratio 25, as pour_3d's steel on glass), alone and five pairs stacked:
// "nlgs" crawls at rho = 0.981 per sweep (739 and 7,442 sweeps to 1e-8, test_nncg_solver.cpp);
// the subspace step is exact on the closed chain whatever the masses.
TEST(SubspaceGaussSeidel, HeavyOnLightColumnsCarryTheirWeights) {
  const double light = sphere_mass(kRadius, kDensity), heavy = 25.0 * light;
  EXPECT_LE(column_solved({light, heavy}, 1e-8), 10);
  std::vector<double> tall;
  for (int k = 0; k < 5; ++k) tall.insert(tall.end(), {light, heavy});
  EXPECT_LE(column_solved(tall, 1e-8), 10);
}

// The frictional 5 x 5 x 6 lattice pile (hyperstatic only through its side contacts, which
// carry nothing): statics and "nlgs"'s reactions, natural-map residual of the tolerance, in
// fewer sweeps than "nlgs".
TEST(SubspaceGaussSeidel, FrictionalLatticePileMatchesGaussSeidelAndStatics) {
  constexpr double tolerance = 1e-8;
  expect_pile_solved_like_gauss_seidel("nlgs_subspace", tolerance, 2.0 * tolerance);
  const ContactProblem& problem = lattice_pile().problem();
  const Solved plain = solve_cold(problem, "nlgs", tolerance);
  const Solved subspace = solve_cold(problem, "nlgs_subspace", tolerance);
  EXPECT_LE(subspace.report.sweeps, plain.report.sweeps / 4)
      << plain.report.sweeps << " against " << subspace.report.sweeps;
}

// Random problems (RandomContactProblem.h: 160 contacts between 40 spheres, open, sticking and
// sliding, a floor and a piston, rolling resistance), cold, both variants: converged, the
// natural-map residual with the rolling blocks at most twice the tolerance, every reaction in
// its cone. Seed 1 is where the subspace step matters: "nlgs" and "nncg" stall on it (at 1e-3
// and 1e-5), both subspace variants converge in 15 sweeps (measured). The 2D problems are
// left out: no solver converges on them (all stall at 2e-6 to 4e-4, measured).
TEST(SubspaceGaussSeidel, RandomProblemsSolvedToTolerance) {
  constexpr double tolerance = 1e-8;
  for (const std::string name : {"nlgs_subspace", "nncg_subspace"}) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(testing::Message() << name << ", seed " << seed);
      const ContactProblem problem = random_contact_problem(3, seed);
      const auto solver = make_contact_solver(name, test::tight(tolerance));
      std::vector<Vector3d> r(problem.size(), Vector3d::Zero()), m = r, v, w;
      const SolveReport report = solver->solve_with_rolling(problem, r, m, v, w);
      ASSERT_TRUE(report.converged) << report.residual << " after " << report.sweeps;
      EXPECT_LE(natural_map_residual(problem, r, m, v, w), 2.0 * tolerance);
      double largest = 0.0;
      for (const Vector3d& x : r) largest = std::max(largest, x.norm());
      ASSERT_GT(largest, 0.0);
      EXPECT_LE(cone_overshoot(problem, r), 1e-12 * largest);
      if (seed == 1) {
        EXPECT_LE(report.sweeps, 100);
      }
    }
  }
}

// The stored steps of column_in_air (3D, a plateau of "nncg") and bed_in_air (2D, a drift of
// "nncg"), from the runs' warm starts at the runs' tolerances, with "nncg_subspace": converged,
// the natural-map residual at most twice the tolerance, every reaction in its cone. There the
// sweeps do not find the active set and the subspace steps are rejected (measured): it is
// "nncg" (2,582 and 1,998 sweeps); "nlgs_subspace" stalls there as "nlgs" does.
TEST(SubspaceGaussSeidel, StoredExampleProblemsSolvedToTolerance) {
  for (const std::string name : {"nncg_plateau_column_in_air.txt", "nncg_drift_bed_in_air.txt"}) {
    SCOPED_TRACE(name);
    const ContactProblemFile f = stored_problem(name);
    SolverSettings settings;
    settings.tolerance = f.tolerance;
    settings.max_iterations = 20000;
    Solved s;
    s.r = f.r;
    s.report = make_contact_solver("nncg_subspace", settings)->solve(f.problem, s.r, s.v, s.w);
    ASSERT_TRUE(s.report.converged) << s.report.residual << " after " << s.report.sweeps;
    EXPECT_LE(natural_map_residual(f.problem, s.r, s.v, s.w), 2.0 * f.tolerance);
    double largest = 0.0;
    for (const Vector3d& x : s.r) largest = std::max(largest, x.norm());
    ASSERT_GT(largest, 0.0);
    EXPECT_LE(cone_overshoot(f.problem, s.r), 1e-12 * largest);
  }
}

// The settled 2D frictional pile (mu = 0.5, hyperstatic: its reactions are not unique): cold,
// "nlgs_subspace" and "nncg" both converge, and the reactions they find carry the same total
// normal impulse and the same weight on the floor (the floor's vertical impulse is the pile's
// weight over the step, whatever the distribution).
TEST(SubspaceGaussSeidel, SettledPileCarriesTheSameTotalNormalImpulseAsNncg) {
  NscdIntegrator sim = settled_disk_pile();
  ASSERT_LT(sim.max_speed(), 1e-9);
  sim.step();
  const ContactProblem& problem = sim.problem();
  constexpr double tolerance = 1e-8;
  const Solved conjugate = solve_cold(problem, "nncg", tolerance);
  const Solved subspace = solve_cold(problem, "nlgs_subspace", tolerance);
  ASSERT_TRUE(conjugate.report.converged);
  ASSERT_TRUE(subspace.report.converged) << subspace.report.residual << " after " << subspace.report.sweeps;
  EXPECT_LE(natural_map_residual(problem, subspace.r, subspace.v, subspace.w), 2.0 * tolerance);
  double weight = 0.0, floor = 0.0, normal_nncg = 0.0, normal_subspace = 0.0;
  for (double mass : sim.particles().mass) weight += mass * kG * sim.parameters().time_step;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (problem.body_j[c] == wall_code<std::int32_t>(0)) floor += global_impulse(problem, c, subspace.r[c]).y();
    normal_nncg += conjugate.r[c][0];
    normal_subspace += subspace.r[c][0];
  }
  EXPECT_NEAR(floor, weight, 1e-5 * weight);
  EXPECT_NEAR(normal_subspace, normal_nncg, 1e-3 * normal_nncg);
}
