// NscdIntegrator::hold_initial_overlaps: the overlaps a bed starts with (an imported packing
// made at a softened modulus) are held by the position step. Against exact answers: a column
// of spheres overlapping by 3% of a radius stays where it is, each contact carrying the weight
// above it, where without the hold the position step pushes every pair apart; a held overlap
// only shrinks (a pair that opens loses it for good, and closing again it is corrected to the
// slop like any other); the held overlaps survive save_state / restore_state bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

constexpr int kCount = 10;
constexpr double kOverlap = 0.03 * kRadius;  // each pair's, and the bottom sphere's with the floor

// kCount spheres stacked along y, each overlapping the one below (and the floor) by kOverlap.
NscdIntegrator overlapping_column(bool hold) {
  ParticleSet set;
  for (int k = 0; k < kCount; ++k)
    set.add(Vector3d(0, kRadius - kOverlap + k * (2 * kRadius - kOverlap), 0), kRadius,
            sphere_mass(kRadius, kDensity), 0);
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-9;
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, parameters);
  if (hold) sim.hold_initial_overlaps(std::vector<std::uint8_t>(kCount, 1));
  return sim;
}

}  // namespace

TEST(HeldOverlaps, OverlappingColumnStaysWhereItIsAndCarriesItsWeight) {
  NscdIntegrator sim = overlapping_column(true);
  const std::vector<Vector3d> start = sim.particles().position;
  const double weight = sphere_mass(kRadius, kDensity) * kG;
  for (int step = 0; step < 200; ++step) ASSERT_TRUE(sim.step().converged) << step;
  EXPECT_EQ(sim.held_overlaps(), static_cast<std::size_t>(kCount));  // 9 pairs and the floor
  EXPECT_NEAR(sim.largest_held_overlap_m(), kOverlap, 1e-12 * kRadius);
  for (int k = 0; k < kCount; ++k)
    EXPECT_LT((sim.particles().position[k] - start[k]).norm(), 1e-12 * kRadius) << k;
  // Contact k carries the weight of the spheres above its lower body (the floor's: all of them).
  ASSERT_EQ(sim.contacts().size(), static_cast<std::size_t>(kCount));
  for (const ContactForce& c : sim.contacts()) {
    const int above = c.j < 0 ? kCount : kCount - c.j;
    EXPECT_NEAR(c.normal_force_N, above * weight, 1e-6 * kCount * weight) << c.i << " " << c.j;
  }
  EXPECT_EQ(sim.stats().correction_sweeps, 0);
}

// The same column without the hold: the position step removes the overlaps, so every sphere
// rises, the top one by about kCount overlaps (the contrast the hold is for).
TEST(HeldOverlaps, WithoutTheHoldThePositionStepPushesThePairsApart) {
  NscdIntegrator sim = overlapping_column(false);
  const double top = sim.particles().position[kCount - 1].y();
  for (int step = 0; step < 200; ++step) sim.step();
  EXPECT_EQ(sim.held_overlaps(), 0u);
  EXPECT_GT(sim.stats().correction_sweeps, 0);
  EXPECT_GT(sim.particles().position[kCount - 1].y() - top, 0.9 * kCount * kOverlap);
}

// Two spheres overlapping, moving apart without gravity: the hold goes as they open; sent back
// towards each other, they meet as any pair does (held nothing: the overlap is at most the
// slop's band, not kOverlap).
TEST(HeldOverlaps, AHeldOverlapOnlyShrinksAndIsGoneOnceThePairOpens) {
  ParticleSet set;
  set.add(Vector3d(-kRadius + kOverlap / 2, 0, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  set.add(Vector3d(kRadius - kOverlap / 2, 0, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  set.velocity[0] = Vector3d(-1e-3, 0, 0);
  set.velocity[1] = Vector3d(1e-3, 0, 0);
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {}, Vector3d::Zero(), 3, nlgs_parameters());
  sim.hold_initial_overlaps({1, 1});
  sim.step();
  // After one step of 1e-3 s the pair opened by 2e-6 m of its overlap.
  EXPECT_EQ(sim.held_overlaps(), 1u);
  EXPECT_NEAR(sim.largest_held_overlap_m(), kOverlap - 2e-6, 1e-12);
  const int steps_to_open = static_cast<int>(std::ceil(kOverlap / 2e-6)) + 2;
  for (int step = 0; step < steps_to_open; ++step) sim.step();
  EXPECT_EQ(sim.held_overlaps(), 0u);
  EXPECT_EQ(sim.largest_held_overlap_m(), 0.0);
  // Back together at 1 m/s: the step stops them at contact (inelastic), nothing held.
  sim.particles().velocity[0] = Vector3d(1.0, 0, 0);
  sim.particles().velocity[1] = Vector3d(-1.0, 0, 0);
  double deepest = 0.0;
  for (int step = 0; step < 50; ++step) {
    const StepReport report = sim.step();
    deepest = std::max(deepest, report.max_penetration_m);
  }
  EXPECT_EQ(sim.held_overlaps(), 0u);
  EXPECT_LT(deepest, 0.1 * kOverlap);
}

// A state saved mid-run carries the held overlaps: the restored integrator steps on bit for bit.
TEST(HeldOverlaps, HeldOverlapsSurviveSaveAndRestore) {
  NscdIntegrator first = overlapping_column(true);
  for (int step = 0; step < 5; ++step) first.step();
  const MechanicsState saved = first.save_state();
  ASSERT_EQ(saved.candidate_held_overlap_m.size(), saved.candidates.size());
  NscdIntegrator second = overlapping_column(false);
  second.restore_state(saved);
  EXPECT_EQ(second.held_overlaps(), first.held_overlaps());
  for (int step = 0; step < 20; ++step) {
    first.step();
    second.step();
  }
  for (int k = 0; k < kCount; ++k) EXPECT_EQ(first.particles().position[k], second.particles().position[k]) << k;
  EXPECT_EQ(second.stats().correction_sweeps, first.stats().correction_sweeps);
}
