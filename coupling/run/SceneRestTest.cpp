#include "coupling/run/SceneRestTest.h"

#include <cmath>

namespace tmdem::coupling {

SceneRestTest::SceneRestTest(const Scene& scene, const mechanics::NscdIntegrator& nscd)
    : nscd_(nscd),
      settle_velocity_m_per_s_(scene.mechanics.settle_velocity_m_per_s),
      network_test_(scene.mechanics.rest_test == "network"),
      network_({.window_steps = scene.mechanics.rest_window,
                .gravity_m_s2 = nscd.gravity(),
                .force_change = scene.mechanics.rest_force_change,
                .speed_m_s = scene.mechanics.settle_velocity_m_per_s}) {}

bool SceneRestTest::after_step() {
  const bool network_at_rest = network_.after_step(nscd_.contacts(), nscd_.particles());
  // A packing is at rest only on a step solved at `tolerance`, not during the ramp after a
  // fall or a compaction (ToleranceSchedule.h): the packing handed to the heat carries the
  // tolerance's forces. A pressed 540-sphere bed came to rest 14 steps into its ramp (1.8e-5)
  // with an overlap 2.6e-4 of its radius, past the 2e-4 the position step holds. A fall that
  // never ends (a rattler above fall_speed) is not waited for: that phase is not `Landed`.
  if (nscd_.tolerance_schedule().phase() == mechanics::ToleranceSchedule::Phase::Landed &&
      nscd_.tolerance_in_force() > nscd_.parameters().tolerance)
    return false;
  if (!network_test_) return nscd_.max_speed() < settle_velocity_m_per_s_;
  // A piston still on its way down changes the load the network is about to carry: the bed is
  // not at rest until every piston is as slow as a load carrier must be (a piston started above
  // a bed would otherwise be frozen in the air, and a conductivity study see no cold wall).
  for (const auto& wall : nscd_.walls())
    if (wall.moves() && !(std::abs(wall.velocity_m_per_s) < settle_velocity_m_per_s_)) return false;
  return network_at_rest;
}

}  // namespace tmdem::coupling
