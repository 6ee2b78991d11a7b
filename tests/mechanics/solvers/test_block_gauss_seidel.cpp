// Gauss-Seidel with a block visit per light body ("nlgs_block", BlockGaussSeidelSolver.h):
// the closed-form statics of heavy-on-light columns in a few sweeps where plain Gauss-Seidel
// crawls at its predicted contraction, the same answer as "nlgs" on a settled frictional pile,
// and a pile settled with it stays at rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/ColumnStatics.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/BlockGaussSeidelSolver.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/model/PairIndex.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

struct Counts {
  int plain = 0, block = 0;
};

// Both solvers cold on the column's problem; each answer checked against the statics to the
// error its stop test allows (plain: tolerance / (1 - rho); block: a few times tolerance).
Counts solve_column_both_ways(const NscdIntegrator& sim, double tolerance, double rho) {
  Counts counts;
  for (const char* name : {"nlgs", "nlgs_block"}) {
    SCOPED_TRACE(name);
    const bool plain = std::string(name) == "nlgs";
    const Solved s = solve_cold(sim.problem(), name, tolerance);
    EXPECT_TRUE(s.report.converged) << s.report.residual;
    expect_column_statics(sim, s.r, plain ? 2.0 * tolerance / (1.0 - rho) : 10.0 * tolerance);
    (plain ? counts.plain : counts.block) = s.report.sweeps;
  }
  return counts;
}

}  // namespace

TEST(BlockGaussSeidel, IsRegisteredByName) {
  const auto& names = contact_solver_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "nlgs_block"), names.end());
  EXPECT_EQ(make_contact_solver("nlgs_block", {})->name(), "nlgs_block");
}

// 0.5 mm glass under 1 mm steel (mass ratio 25, as in examples/pour_3d.toml): the block of
// the light sphere is exact in one visit, so the second sweep finds nothing to change; plain
// Gauss-Seidel takes the sweeps of its contraction law.
TEST(BlockGaussSeidel, HeavyOnLightColumnIsExactInTwoSweeps) {
  const double light = sphere_mass(kRadius, kDensity), heavy = 25.0 * light;
  const NscdIntegrator sim = column({light, heavy});
  constexpr double tolerance = 1e-8;
  const double rho = plain_contraction(light, heavy);  // 0.981
  const Counts counts = solve_column_both_ways(sim, tolerance, rho);
  const double predicted = std::log(tolerance) / std::log(rho);  // 940 sweeps
  EXPECT_GT(counts.plain, 0.7 * predicted);
  EXPECT_LT(counts.plain, 1.3 * predicted);
  EXPECT_LE(counts.block, 2);
}

// Light, heavy, light: the bottom light sphere is a block (floor and heavy contacts), the top
// one too (its single contact with the heavy one). The two blocks talk through the heavy
// sphere: the top contact's visit moves it by a / (a + b) of the correction, which the bottom
// block then takes up, so the block sweeps contract by a / (a + b) = 1/26 (pairs of blocks
// visited in both orders: at most twice ln(tolerance) / ln(a / (a + b)) sweeps), where plain
// Gauss-Seidel still crawls at rho.
TEST(BlockGaussSeidel, LightHeavyLightColumnIsExactInAFewSweeps) {
  const double light = sphere_mass(kRadius, kDensity), heavy = 25.0 * light;
  const NscdIntegrator sim = column({light, heavy, light});
  constexpr double tolerance = 1e-8;
  const double rho = plain_contraction(light, heavy);
  const Counts counts = solve_column_both_ways(sim, tolerance, rho);
  const double a = 1.0 / heavy, b = 1.0 / light;
  EXPECT_GT(counts.plain, 0.7 * std::log(tolerance) / std::log(rho));
  EXPECT_LE(counts.block, 2.0 * std::log(tolerance) / std::log(a / (a + b)) + 1.0);  // 12.3
}

// Equal masses: no body is lighter than its neighbour by the ratio, no block, and the sweeps
// are exactly those of "nlgs" (same order, same visits).
TEST(BlockGaussSeidel, WithoutLightBodiesItIsPlainGaussSeidel) {
  const double m = sphere_mass(kRadius, kDensity);
  const NscdIntegrator sim = column({m, m, m, m});
  const Solved plain = solve_cold(sim.problem(), "nlgs", 1e-10);
  BlockGaussSeidelSolver block(tight(1e-10));
  const Solved blocked = solve_cold(sim.problem(), block);
  EXPECT_EQ(block.block_count(), 0u);
  EXPECT_EQ(plain.report.sweeps, blocked.report.sweeps);
  EXPECT_EQ(largest_difference(plain.r, blocked.r), 0.0);
}

// The settled 2D pile of the rest tests (radii 1 and 0.7 mm: mass ratio 2.9, so the small disks
// under large ones get blocks), mu = 0.5. Its reactions are not unique (a frictional pile is
// hyperstatic: cold solves of "nlgs" and "nlgs_block" differ by up to a quarter of the largest
// reaction, measured), so the two are compared by what any solution satisfies: the natural-map
// residual, the floor carrying the weight, every reaction in its cone; and by their fixed
// points: each solver, started from the other's answer, stops at once without moving it.
TEST(BlockGaussSeidel, SettledFrictionalPileLikeGaussSeidel) {
  NscdIntegrator sim = settled_disk_pile();
  ASSERT_LT(sim.max_speed(), 1e-9);
  sim.step();
  const ContactProblem& problem = sim.problem();
  constexpr double tolerance = 1e-8;
  BlockGaussSeidelSolver block(tight(tolerance));
  const Solved blocked = solve_cold(problem, block);
  const Solved plain = solve_cold(problem, "nlgs", tolerance);
  ASSERT_TRUE(blocked.report.converged) << blocked.report.residual;
  ASSERT_TRUE(plain.report.converged);
  EXPECT_GT(block.block_count(), 3u);  // the blocks are really used ...
  EXPECT_LT(block.block_fallbacks(), block.block_visits() / 20);  // ... and nearly always solved
  EXPECT_LE(natural_map_residual(problem, blocked.r, blocked.v, blocked.w), 2.0 * tolerance);
  double weight_Ns = 0.0, floor_Ns = 0.0, largest = 0.0;
  for (double m : sim.particles().mass) weight_Ns += m * kG * sim.parameters().time_step;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    const Vector3d& r = blocked.r[c];
    EXPECT_GE(r[0], 0.0);
    EXPECT_LE(r.tail<2>().norm(), problem.mu[c] * r[0] * (1.0 + 1e-12));
    if (problem.body_j[c] == wall_code<std::int32_t>(0)) floor_Ns += global_impulse(problem, c, r).y();
    largest = std::max(largest, plain.r[c].norm());
  }
  EXPECT_NEAR(floor_Ns, weight_Ns, 1e-5 * weight_Ns);
  // Same fixed points: each solver, from the other's answer, stops within two sweeps and moves
  // it by no more than the tolerance allows. "nlgs"'s answer is taken at 1e-13: at 1e-8 its
  // stop test leaves an error of 1e-6 of the largest reaction in its slow mode (tolerance /
  // (1 - contraction)), which the block solve then removes (measured: 62 sweeps, 3.3e-12 N s).
  const Solved plain_tight = solve_cold(problem, "nlgs", 1e-13);
  ASSERT_TRUE(plain_tight.report.converged);
  for (const bool block_from_plain : {true, false}) {
    SCOPED_TRACE(block_from_plain ? "nlgs_block from nlgs" : "nlgs from nlgs_block");
    const std::vector<Vector3d>& start = block_from_plain ? plain_tight.r : blocked.r;
    std::vector<Vector3d> r = start, v, w;
    BlockGaussSeidelSolver again_block(tight(tolerance));
    auto again_plain = make_contact_solver("nlgs", tight(tolerance));
    ContactSolver& again = block_from_plain ? static_cast<ContactSolver&>(again_block) : *again_plain;
    const SolveReport report = again.solve(problem, r, v, w);
    EXPECT_TRUE(report.converged);
    EXPECT_LE(report.sweeps, 2);
    EXPECT_LE(largest_difference(r, start), 10.0 * tolerance * largest);
  }
}

// At rest means at rest with "nlgs_block" too: the pile of NscdRest.RestingPileStaysAtRestFor10000Steps
// (settled with "nlgs"), carried on with "nlgs_block" (a new integrator from the same particles:
// its first steps start cold, so 200 steps first), stays put for 10,000 steps.
// Not the pile settled with "nlgs_block" from the start: its path leaves a different packing,
// which creeps at a few 1e-8 m/s under either solver at tolerance 1e-8 (measured over 2,000
// steps: "nlgs" 6.4e-8 m/s, moved 1.1e-7 m; "nlgs_block" 4.8e-8 m/s, 7.3e-8 m) and settles at
// tolerance 1e-11 (1.2e-10 m/s, moved 3e-11 m over 1,000 steps).
TEST(BlockGaussSeidel, RestingPileStaysAtRestFor10000Steps) {
  std::unique_ptr<NscdIntegrator> sim;
  const Drift drift = drift_at_rest_with("nlgs_block", sim);
  EXPECT_LT(drift.fastest_m_per_s, 1e-8);
  EXPECT_LT(drift.moved_m, 1e-9);
  const auto& solver = dynamic_cast<const BlockGaussSeidelSolver&>(sim->solver());
  EXPECT_GT(solver.block_count(), 3u);  // the blocks are there at rest too
}

// With rolling resistance (the rolling blocks stay single visits after each block's (n, t)
// solve): a 3D pile (radii 1 and 0.7 mm, mu = 0.5, mu_r = 0.1) settled with "nlgs", its last
// problem solved cold by "nlgs_block": the natural-map residual of the tolerance with the
// rolling blocks counted, every reaction within both cones, and the pile left at rest, as
// "nlgs" leaves it (RollingFriction.EverySolverMatchesGaussSeidelWithSameBitsForAnyThreadCount).
TEST(BlockGaussSeidel, RollingPileLikeGaussSeidel) {
  const NscdIntegrator sim = settled_rolling_pile();
  BlockGaussSeidelSolver block(tight(1e-7));
  expect_rolling_pile_solved(sim, block, 1e-7);
  EXPECT_GT(block.block_count(), 0u);
}
