#include "coupling/studies/ThermalReplay.h"

#include <algorithm>
#include <limits>

namespace tmdem::coupling {

ThermalReplay::ThermalReplay(const Scene& scene, const ContactRecording& recording,
                             thermal::ThermalSystem& system)
    : recording_(recording), system_(system), network_(scene, system) {}

double ThermalReplay::min_stability_bound_s(double max_temperature_K) {
  network_.reset();
  double bound = std::numeric_limits<double>::infinity();
  for (const auto& contacts : recording_.contacts) {
    network_.load(contacts);
    bound = std::min(bound, system_.explicit_stability_bound_s(max_temperature_K));
  }
  return bound;
}

void ThermalReplay::run(thermal::ThermalIntegrator& integrator, std::span<const double> T0_K,
                        CouplingStrategy coupling) {
  network_.reset();
  integrator.initialize(0.0, T0_K, 0.0);
  for (std::size_t k = 0; k < recording_.step_end_s.size(); ++k) {
    step_contacts_ = recording_.contacts[k];  // copied: update fills in conductances
    network_.update(step_contacts_, integrator, coupling);
    integrator.advance_to(recording_.step_end_s[k]);
  }
}

}  // namespace tmdem::coupling
