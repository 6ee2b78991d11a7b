// Properties that must hold for every contact and every step of a settling random pile:
// reactions in the Coulomb cone, no energy growth, 2D runs exactly planar, no allocation
// once warm, no penetration build-up.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <utility>

#include "mechanics/model/PairIndex.h"

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

// Counts heap allocations while enabled (replaces the global operator new for this program).
static std::atomic<bool> g_count_allocations{false};
static std::atomic<long> g_allocations{0};
void* operator new(std::size_t size) {
  if (g_count_allocations.load(std::memory_order_relaxed)) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// The nothrow form too (std::stable_sort's temporary buffer uses it): otherwise its memory
// comes from the library's operator new and goes back through the free() below, which ASan
// reports as an alloc-dealloc mismatch.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (g_count_allocations.load(std::memory_order_relaxed)) ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
// The replaced operator new uses malloc, so free is the matching release (GCC cannot see
// the replacement and warns otherwise).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
#pragma GCC diagnostic pop

// The properties below do not depend on how tightly each step is solved, so most tests use
// a loose tolerance to stay fast; the energy test needs a tight one (see there).
NscdParameters loose() {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-4;
  return parameters;
}

TEST(NscdPile, ReactionsStayInTheCoulombCone3D) {
  const double mu = 0.3;
  auto sim = random_pile(60, 3, mu, 5, loose());
  std::size_t checked = 0, sliding = 0;
  for (int step = 0; step < 300; ++step) {
    sim.step();
    for (const ContactForce& c : sim.contacts()) {
      ASSERT_GE(c.normal_force_N, 0.0);
      const double rt = c.tangential_force_N.norm();
      ASSERT_LE(rt, mu * c.normal_force_N * (1 + 1e-9)) << "step " << step;
      ASSERT_LT(std::abs(c.tangential_force_N.dot(c.normal)), 1e-12 * (rt + c.normal_force_N));
      if (rt > mu * c.normal_force_N * (1 - 1e-6)) ++sliding;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000u);
  EXPECT_GT(sliding, 10u);  // the cone boundary was reached, so the check had teeth
  // Overlaps are held up to twice the slop (PenetrationCorrection.h), r_min = 0.7 kRadius.
  EXPECT_LT(sim.stats().max_penetration_m, PenetrationCorrection::kTrigger *
                                               sim.parameters().penetration_slop_fraction * 0.7 * kRadius *
                                               (1 + PenetrationCorrection::kTolerance));
}

// Energy per step may only fall: with theta = 1/2 the flight is exactly conservative and
// contacts dissipate. The growth seen in practice comes from the inexact contact solve and
// scales with the tolerance (for a 100-particle 2D pile about 2e-9 of E at 1e-6, 7e-11 at
// 1e-10), so the solver runs at 1e-9 here and the allowance is 1e-9 of the initial energy
// (potential energy counted from the floor).
void expect_energy_never_grows(std::size_t count, int dimension, double mu, int steps) {
  NscdParameters parameters = nlgs_parameters();
  parameters.tolerance = 1e-9;
  auto sim = random_pile(count, dimension, mu, 9, parameters);
  const double initial = sim.kinetic_energy() + sim.potential_energy();
  ASSERT_GT(initial, 0.0);
  double previous = initial;
  for (int step = 0; step < steps; ++step) {
    sim.step();
    const double energy = sim.kinetic_energy() + sim.potential_energy();
    ASSERT_LE(energy, previous + 1e-9 * initial) << "step " << step;
    previous = energy;
  }
  EXPECT_LT(previous, 0.9 * initial);  // it did fall, collide and lose energy
}

TEST(NscdPile, MechanicalEnergyNeverGrowsDuringSettle2D) { expect_energy_never_grows(40, 2, 0.3, 300); }
TEST(NscdPile, MechanicalEnergyNeverGrowsFrictionless2D) { expect_energy_never_grows(40, 2, 0.0, 300); }
TEST(NscdPile, MechanicalEnergyNeverGrowsDuringSettle3D) { expect_energy_never_grows(60, 3, 0.3, 300); }

TEST(NscdPile, TwoDimensionalRunStaysExactlyInPlane) {
  auto sim = random_pile(80, 2, 0.4, 2, loose());
  // A spinning, sideways start: any out-of-plane leak would show up.
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    sim.particles().angular_velocity[i] = Eigen::Vector3d(0, 0, 10.0 * ((i % 3) - 1.0));
    sim.particles().velocity[i] = Eigen::Vector3d(0.01 * ((i % 5) - 2.0), 0, 0);
  }
  std::size_t active = 0;
  for (int step = 0; step < 300; ++step) {
    sim.step();
    const auto& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_EQ(p.position[i].z(), 0.0);
      ASSERT_EQ(p.velocity[i].z(), 0.0);
      ASSERT_EQ(p.angular_velocity[i].x(), 0.0);
      ASSERT_EQ(p.angular_velocity[i].y(), 0.0);
    }
    for (const ContactForce& c : sim.contacts()) {
      ASSERT_EQ(c.normal.z(), 0.0);
      ASSERT_EQ(c.tangential_force_N.z(), 0.0);
    }
    active = sim.contacts().size();
  }
  EXPECT_GT(active, 80u);
}

TEST(NscdPile, NoAllocationOnceWarm) {
  auto sim = random_pile(60, 3, 0.3, 4, loose());
  // The counter works: the first steps allocate (tables grow).
  g_allocations = 0;
  g_count_allocations = true;
  sim.step();
  g_count_allocations = false;
  EXPECT_GT(g_allocations.load(), 0);
  for (int step = 0; step < 400; ++step) sim.step();
  g_allocations = 0;
  g_count_allocations = true;
  for (int step = 0; step < 100; ++step) sim.step();
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_GE(sim.contacts().size(), 50u);
}

// Up to 5 s: without rolling resistance a disk left alone on the floor keeps rolling at its
// speed until it meets the pile or a wall (seed 6: one rolls at 1.08e-4 m/s until step 3011).
TEST(NscdPile, SettlesBelowSettleVelocity) {
  auto sim = random_pile(60, 2, 0.5, 6, loose());
  int step = 0;
  for (; step < 5000 && !(step > 10 && sim.max_speed() < 1e-4); ++step) sim.step();
  EXPECT_LT(sim.max_speed(), 1e-4) << "after " << step << " steps";
  // Everything rests on something: each particle has at least one contact.
  std::vector<int> count(sim.particles().size(), 0);
  for (const ContactForce& c : sim.contacts()) {
    ++count[c.i];
    if (c.j >= 0) ++count[c.j];
  }
  for (std::size_t i = 0; i < count.size(); ++i) EXPECT_GE(count[i], 1) << "particle " << i;
}

// The coupling copies contacts() as they come (gather_contacts does not sort), so the order is
// a promise: strictly increasing (i, j), j signed, over every step of a pile with wall contacts.
TEST(NscdPile, ContactsComeInCanonicalOrder) {
  auto sim = random_pile(60, 3, 0.3, 5, loose());
  std::size_t wall_contacts = 0, checked = 0;
  for (int step = 0; step < 300; ++step) {
    sim.step();
    const auto& c = sim.contacts();
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (is_wall(c[k].j)) ++wall_contacts;
      if (k == 0) continue;
      ASSERT_LT(std::pair(c[k - 1].i, c[k - 1].j), std::pair(c[k].i, c[k].j)) << "step " << step;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000u);
  EXPECT_GT(wall_contacts, 100u);  // walls-first ordering was exercised
}
