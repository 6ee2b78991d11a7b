// NscdIntegrator::save_state / restore_state (MechanicsState.h): an integrator built anew from
// the same particles and given a saved state continues bit for bit like the one it was saved
// from, and the state is what makes that true (a restart from positions and velocities alone
// does not).
#include <gtest/gtest.h>

#include <cstring>

#include "mechanics/SameBits.h"
#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace {

using tmdem::mechanics::test::same_bits;


struct Trajectory {
  std::vector<std::vector<Eigen::Vector3d>> position, velocity, angular_velocity;
  std::vector<int> sweeps;
};

Trajectory run_trajectory(NscdIntegrator& nscd, int steps) {
  Trajectory t;
  for (int s = 0; s < steps; ++s) {
    t.sweeps.push_back(nscd.step().sweeps);
    t.position.push_back(nscd.particles().position);
    t.velocity.push_back(nscd.particles().velocity);
    t.angular_velocity.push_back(nscd.particles().angular_velocity);
  }
  return t;
}

// Steps `before` steps, saves, and compares `after` more steps of the original with those of
// a fresh integrator of the same pile restored from the save.
void expect_restored_run_identical(int dimension, double friction, int before, int after,
                                   NscdParameters parameters = nlgs_parameters(), double rolling_friction = 0.0) {
  NscdIntegrator original = random_pile(40, dimension, friction, 7, parameters, rolling_friction);
  for (int s = 0; s < before; ++s) original.step();
  const MechanicsState saved = original.save_state();
  ASSERT_FALSE(saved.candidates.empty());
  ASSERT_EQ(saved.candidate_force_N.size(), saved.candidates.size());

  NscdIntegrator restored = random_pile(40, dimension, friction, 7, parameters, rolling_friction);
  ASSERT_EQ(saved.candidate_rolling_torque_Nm.size(),
            rolling_friction > 0.0 ? saved.candidates.size() : 0u);
  restored.restore_state(saved);
  EXPECT_EQ(restored.stats().steps, before);
  EXPECT_EQ(restored.detector().rebuild_count(), original.detector().rebuild_count());

  const Trajectory a = run_trajectory(original, after), b = run_trajectory(restored, after);
  for (int s = 0; s < after; ++s) {
    ASSERT_TRUE(same_bits(a.position[s], b.position[s])) << "step " << s;
    ASSERT_TRUE(same_bits(a.velocity[s], b.velocity[s])) << "step " << s;
    ASSERT_TRUE(same_bits(a.angular_velocity[s], b.angular_velocity[s])) << "step " << s;
    ASSERT_EQ(a.sweeps[s], b.sweeps[s]) << "step " << s;
  }
  EXPECT_EQ(original.stats().total_sweeps, restored.stats().total_sweeps);
  EXPECT_EQ(original.detector().rebuild_count(), restored.detector().rebuild_count());

  // Positions and velocities alone (a cold restart: fresh table, no warm start) give another
  // run: the Gauss-Seidel solve starts elsewhere and stops at another iterate.
  NscdIntegrator cold = random_pile(40, dimension, friction, 7, parameters, rolling_friction);
  cold.particles().position = saved.position_m;
  cold.particles().velocity = saved.velocity_m_per_s;
  cold.particles().angular_velocity = saved.angular_velocity_rad_per_s;
  cold.invalidate_contacts();
  const Trajectory c = run_trajectory(cold, after);
  bool differs = false;
  for (int s = 0; s < after && !differs; ++s) differs = !same_bits(a.velocity[s], c.velocity[s]);
  EXPECT_TRUE(differs) << "a cold restart should not reproduce the run; the test would prove nothing";
}

}  // namespace

TEST(NscdState, RestoredIntegratorContinuesBitwise2D) { expect_restored_run_identical(2, 0.3, 150, 150); }
TEST(NscdState, RestoredIntegratorContinuesBitwise3D) { expect_restored_run_identical(3, 0.3, 120, 120); }
// apgd carries its step-size (Lipschitz) estimate from solve to solve: part of the state.
TEST(NscdState, RestoredApgdIntegratorContinuesBitwise) {
  NscdParameters parameters = nlgs_parameters();
  parameters.solver = "apgd";
  expect_restored_run_identical(2, 0.3, 150, 150, parameters);
}

// Rolling resistance carries each candidate's rolling torque as the warm start: part of the state.
TEST(NscdState, RestoredIntegratorWithRollingFrictionContinuesBitwise) {
  expect_restored_run_identical(3, 0.3, 120, 120, {}, 0.1);
}
// apgd with rolling resistance: the rolling torques and the Lipschitz estimate together.
TEST(NscdState, RestoredApgdIntegratorWithRollingFrictionContinuesBitwise) {
  NscdParameters parameters = nlgs_parameters();
  parameters.solver = "apgd";
  expect_restored_run_identical(2, 0.3, 100, 100, parameters, 0.1);
}

// The solver given the problem in a spatial order (SpatialContactOrder.h): the order comes
// from the candidate table's reference positions, which the state carries.
TEST(NscdState, RestoredIntegratorInSpatialOrderContinuesBitwise) {
  NscdParameters parameters = nlgs_parameters();
  parameters.spatial_order_from = 0;
  expect_restored_run_identical(3, 0.3, 120, 120, parameters, 0.1);
}

TEST(NscdState, StateOfAnotherPileIsRefused) {
  NscdIntegrator small = random_pile(10, 2, 0.3, 1), large = random_pile(40, 2, 0.3, 1);
  large.step();
  EXPECT_THROW(small.restore_state(large.save_state()), std::invalid_argument);
  auto state = large.save_state();
  state.candidate_force_N.pop_back();
  EXPECT_THROW(large.restore_state(state), std::invalid_argument);
}
