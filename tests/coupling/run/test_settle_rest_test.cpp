// The network rest test of the settle phase (coupling/run/SettleRestTest.h) on hand-made steps:
// it waits exactly one window of stationary forces, ignores rattlers and particles that carry
// nothing but their own weight, counts an opened contact with its whole force, and falls back
// on every particle's speed where nothing carries force.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/run/SettleRestTest.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::coupling {
namespace {

using mechanics::ContactForce;
using mechanics::ParticleSet;

ContactForce contact(std::int64_t i, std::int64_t j, double force_N) {
  ContactForce c;
  c.i = i;
  c.j = j;
  c.normal_force_N = force_N;
  return c;
}

// Three particles: 0 on the floor, 1 on 0, 2 a rattler touching nobody.
ParticleSet three_particles() {
  ParticleSet p;
  for (int k = 0; k < 3; ++k) p.add({0.0, 0.002 * k, 0.0}, 1e-3, 1e-5, 0);
  return p;
}

// Particles of 1e-5 kg under 9.81 m/s^2: a weight of 9.81e-5 N each.
SettleRestTestSettings settings(int window, double force_change = 1e-2) {
  return {.window_steps = window, .gravity_m_s2 = {0.0, -9.81, 0.0}, .force_change = force_change,
          .speed_m_s = 1e-4};
}

ContactForce contact(std::int64_t i, std::int64_t j, double force_N, const Eigen::Vector3d& normal) {
  ContactForce c = contact(i, j, force_N);
  c.normal = normal;
  return c;
}

std::vector<ContactForce> carried_column(double floor_N, double pair_N) {
  return {contact(0, mechanics::wall_code<std::int64_t>(0), floor_N), contact(0, 1, pair_N)};
}

TEST(SettleRestTest, WaitsOneWindowOfStationaryForces) {
  SettleRestTest rest(settings(3));
  const auto particles = three_particles();
  for (int step = 1; step <= 3; ++step)
    EXPECT_FALSE(rest.after_step(carried_column(2e-4, 1e-4), particles)) << "step " << step;
  EXPECT_TRUE(rest.after_step(carried_column(2e-4, 1e-4), particles));
  EXPECT_EQ(rest.force_change(), 0.0);
  EXPECT_EQ(rest.rattlers(), 1);
}

TEST(SettleRestTest, RattlerDoesNotHoldItUpButLoadCarriersDo) {
  SettleRestTest rest(settings(1));
  auto particles = three_particles();
  particles.velocity[2] = {0.0, -0.5, 0.0};  // a rattler falling through a pore
  EXPECT_FALSE(rest.after_step(carried_column(2e-4, 1e-4), particles));
  EXPECT_TRUE(rest.after_step(carried_column(2e-4, 1e-4), particles));
  EXPECT_EQ(rest.rattlers(), 1);
  // A load carrier at 2e-4 m/s: sqrt(2 KE / M) = 2e-4 / sqrt(2) = 1.41e-4 m/s > 1e-4.
  particles.velocity[1] = {2e-4, 0.0, 0.0};
  EXPECT_FALSE(rest.after_step(carried_column(2e-4, 1e-4), particles));
  EXPECT_NEAR(rest.load_speed_m_s(), 2e-4 / std::sqrt(2.0), 1e-18);
}

// A particle sliding down a pore grazes a neighbour with much less than its weight: it carries
// no load, so its speed holds nothing up; it counts as a rattler.
TEST(SettleRestTest, ParticleHeldByLessThanHalfItsWeightIsNoLoadCarrier) {
  SettleRestTest rest(settings(1));
  auto particles = three_particles();
  particles.velocity[2] = {0.0, -0.05, 0.0};
  auto contacts = carried_column(2e-4, 1e-4);
  contacts.push_back(contact(1, 2, 4.8e-5));  // just under half of 9.81e-5 N
  EXPECT_FALSE(rest.after_step(contacts, particles));
  EXPECT_TRUE(rest.after_step(contacts, particles));
  EXPECT_EQ(rest.rattlers(), 1);
  // Half its weight or more: it carries load, and 0.05 m/s is far too fast.
  contacts.back().normal_force_N = 4.91e-5;
  EXPECT_FALSE(rest.after_step(contacts, particles));
  EXPECT_EQ(rest.rattlers(), 0);
}

// Particle 1 rests on particle 0, which rests on the floor (normals from j to i): 0 is pressed
// down by 1's weight and carries load; 1 carries only its own weight, as a sphere of the free
// surface does, and rolling on it changes nobody's load: its speed holds nothing up. 0's does.
TEST(SettleRestTest, SurfaceParticleCarryingOnlyItsWeightDoesNotHoldItUp) {
  SettleRestTest rest(settings(1));
  auto particles = three_particles();
  const double weight_N = 9.81e-5;
  const std::vector<ContactForce> column = {
      contact(0, mechanics::wall_code<std::int64_t>(0), 2 * weight_N, {0.0, 1.0, 0.0}),
      contact(0, 1, weight_N, {0.0, -1.0, 0.0})};
  particles.velocity[1] = {0.05, 0.0, 0.0};
  EXPECT_FALSE(rest.after_step(column, particles));
  EXPECT_TRUE(rest.after_step(column, particles));
  EXPECT_EQ(rest.load_carriers(), 1);
  EXPECT_EQ(rest.rattlers(), 1);
  EXPECT_EQ(rest.load_speed_m_s(), 0.0);
  particles.velocity[0] = {2e-4, 0.0, 0.0};
  EXPECT_FALSE(rest.after_step(column, particles));
  EXPECT_NEAR(rest.load_speed_m_s(), 2e-4, 1e-18);
  // Particle 1 lighter than half 0's weight on it: nobody is pressed, so every particle held by
  // half its weight counts (0, by the floor; 1 is held by less and is a rattler).
  auto light = column;
  light[1].normal_force_N = 0.49 * weight_N;
  EXPECT_FALSE(rest.after_step(light, particles));
  EXPECT_EQ(rest.load_carriers(), 1);
  EXPECT_EQ(rest.rattlers(), 2);
}

// Two particles side by side on the floor, nobody pressed: each one held by its weight carries
// load, so a layer sliding on the floor (its forces unchanged) is not at rest.
TEST(SettleRestTest, SingleLayerWaitsForEveryParticleHeldByItsWeight) {
  SettleRestTest rest(settings(1));
  auto particles = three_particles();
  particles.position[1] = {0.002, 0.0, 0.0};
  const double weight_N = 9.81e-5;
  const std::vector<ContactForce> layer = {
      contact(0, mechanics::wall_code<std::int64_t>(0), weight_N, {0.0, 1.0, 0.0}),
      contact(1, mechanics::wall_code<std::int64_t>(0), weight_N, {0.0, 1.0, 0.0})};
  particles.velocity[1] = {0.01, 0.0, 0.0};
  EXPECT_FALSE(rest.after_step(layer, particles));
  EXPECT_FALSE(rest.after_step(layer, particles));
  EXPECT_EQ(rest.load_carriers(), 2);
  particles.velocity[1] = {0.0, 0.0, 0.0};
  EXPECT_TRUE(rest.after_step(layer, particles));
}

TEST(SettleRestTest, ForceChangeIsRelativeToTheTotalAndCountsOpenedContacts) {
  SettleRestTest rest(settings(1));
  const auto particles = three_particles();
  rest.after_step(carried_column(2e-4, 1e-4), particles);
  // 6e-6 N more on the floor: 2% of the 3.06e-4 N in all.
  EXPECT_FALSE(rest.after_step(carried_column(2.06e-4, 1e-4), particles));
  EXPECT_NEAR(rest.force_change(), 6e-6 / 3.06e-4, 1e-12);
  // 1e-6 N less: 0.33%, at rest.
  EXPECT_TRUE(rest.after_step(carried_column(2.05e-4, 1e-4), particles));
  // The pair contact opens: its whole 1e-4 N counts against the 2.05e-4 N left.
  EXPECT_FALSE(rest.after_step({contact(0, mechanics::wall_code<std::int64_t>(0), 2.05e-4)}, particles));
  EXPECT_NEAR(rest.force_change(), 1e-4 / 2.05e-4, 1e-12);
  EXPECT_EQ(rest.rattlers(), 2);
}

TEST(SettleRestTest, WithoutForcesEveryParticleMustBeStill) {
  SettleRestTest rest(settings(1));
  auto particles = three_particles();
  particles.velocity[2] = {0.0, 2e-4, 0.0};
  EXPECT_FALSE(rest.after_step({}, particles));
  EXPECT_FALSE(rest.after_step({}, particles));
  particles.velocity[2] = {0.0, 5e-5, 0.0};
  EXPECT_TRUE(rest.after_step({}, particles));
  EXPECT_EQ(rest.rattlers(), 3);
}

TEST(SettleRestTest, RefusesBadSettingsNamingTheKey) {
  EXPECT_THROW(SettleRestTest(settings(0)), std::invalid_argument);
  EXPECT_THROW(SettleRestTest(settings(1, 0.0)), std::invalid_argument);
  try {
    SettleRestTest(settings(1, -1.0));
    ADD_FAILURE() << "a negative rest_force_change was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rest_force_change"), std::string::npos);
  }
}

}  // namespace
}  // namespace tmdem::coupling
