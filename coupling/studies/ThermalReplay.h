#pragma once
// Replays a recorded dynamic contact graph through a thermal integrator exactly as `tmdem run`
// follows a dynamic packing (DynamicNetwork), advancing to the end of each mechanical step.
#include <span>
#include <string>

#include "coupling/studies/ContactRecording.h"
#include "coupling/bridge/DynamicNetwork.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

class ThermalReplay {
 public:
  // `system` must have been built for `scene`; its edges are replaced during the replay.
  ThermalReplay(const Scene& scene, const ContactRecording& recording, thermal::ThermalSystem& system);

  // From t = 0 (no contact) through every recorded step. `integrator` must be built on the
  // same system; it is initialized here.
  void run(thermal::ThermalIntegrator& integrator, std::span<const double> T0_K,
           CouplingStrategy coupling);

  // Smallest explicit stability bound over the recorded steps, s (the system's edges are left
  // as those of the last step).
  double min_stability_bound_s(double max_temperature_K);

 private:
  const ContactRecording& recording_;
  thermal::ThermalSystem& system_;
  DynamicNetwork network_;
  ContactList step_contacts_;
};

}  // namespace tmdem::coupling
