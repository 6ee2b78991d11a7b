#pragma once
// The scene's rest test (mechanics.rest_test) over a settling integrator, asked after every
// step: "network" (SettleRestTest.h: the normal forces stationary and the load carriers still)
// or "velocity" (every particle slower than mechanics.settle_velocity). What settle_packing
// stops on, and so what `tmdem contact-problem --step last` takes as the settled packing.
#include "coupling/run/SettleRestTest.h"
#include "coupling/scene/Scene.h"
#include "mechanics/integrator/NscdIntegrator.h"

namespace tmdem::coupling {

class SceneRestTest {
 public:
  SceneRestTest(const Scene& scene, const mechanics::NscdIntegrator& nscd);

  // After each step of `nscd`: true when the packing is at rest by the scene's test.
  bool after_step();

  bool network_test() const { return network_test_; }
  // The network test's figures of the last step (kept up to date under either test: the
  // rattlers are reported in both cases).
  const SettleRestTest& network() const { return network_; }
  SettleRestTest& network() { return network_; }  // a resumed settle restores its window

 private:
  const mechanics::NscdIntegrator& nscd_;
  double settle_velocity_m_per_s_;
  bool network_test_;
  SettleRestTest network_;
};

}  // namespace tmdem::coupling
