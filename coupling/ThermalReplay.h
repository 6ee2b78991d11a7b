#pragma once
// Replays a recorded dynamic contact graph through a thermal integrator, exactly as `tmdem run`
// follows a dynamic packing: per mechanical step, the sticky contact pattern, the conductances
// of that step, and an advance to the step's end (restarting the integrator every step with the
// "restart" strategy).
#include <span>
#include <string>

#include "coupling/ContactPattern.h"
#include "coupling/ContactRecording.h"
#include "coupling/ThermalNetworkBuilder.h"
#include "thermal/ThermalIntegrator.h"
#include "thermal/ThermalSystem.h"

namespace tmdem::coupling {

class ThermalReplay {
 public:
  // `system` must have been built for `scene`; its edges are replaced during the replay.
  ThermalReplay(const Scene& scene, const ContactRecording& recording, thermal::ThermalSystem& system);

  // Clears the system's edges (t = 0: no contact yet), then steps through the recording.
  // `integrator` must be built on the same system and not yet initialized.
  void run(thermal::ThermalIntegrator& integrator, std::span<const double> T0_K,
           const std::string& coupling);

  // Smallest explicit stability bound over the recorded steps, s (the system's edges are left
  // as those of the last step).
  double min_stability_bound_s(double max_temperature_K);

 private:
  void load_step(std::size_t k);

  const ContactRecording& recording_;
  thermal::ThermalSystem& system_;
  ThermalNetworkBuilder builder_;
  ContactPattern pattern_;
  ContactList pattern_contacts_;
  std::vector<std::uint8_t> pattern_active_;
  thermal::ThermalNetwork edges_;
};

}  // namespace tmdem::coupling
