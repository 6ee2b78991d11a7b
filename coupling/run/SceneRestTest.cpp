#include "coupling/run/SceneRestTest.h"

namespace tmdem::coupling {

SceneRestTest::SceneRestTest(const Scene& scene, const mechanics::NscdIntegrator& nscd)
    : nscd_(nscd),
      settle_velocity_m_per_s_(scene.mechanics.settle_velocity_m_per_s),
      network_test_(scene.mechanics.rest_test == "network"),
      network_({.window_steps = scene.mechanics.rest_window,
                .gravity_m_s2 = nscd.gravity().norm(),
                .force_change = scene.mechanics.rest_force_change,
                .speed_m_s = scene.mechanics.settle_velocity_m_per_s}) {}

bool SceneRestTest::after_step() {
  const bool network_at_rest = network_.after_step(nscd_.contacts(), nscd_.particles());
  return network_test_ ? network_at_rest : nscd_.max_speed() < settle_velocity_m_per_s_;
}

}  // namespace tmdem::coupling
