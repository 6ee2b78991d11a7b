#include "coupling/ThermalReplay.h"

#include <algorithm>
#include <limits>

namespace tmdem::coupling {

ThermalReplay::ThermalReplay(const Scene& scene, const ContactRecording& recording,
                             thermal::ThermalSystem& system)
    : recording_(recording), system_(system), builder_(scene) {}

void ThermalReplay::load_step(std::size_t k) {
  pattern_.update(recording_.contacts[k], pattern_contacts_, pattern_active_);
  builder_.build_edges(pattern_contacts_, edges_, &pattern_active_);
  system_.replace_edges(edges_);
}

double ThermalReplay::min_stability_bound_s(double max_temperature_K) {
  pattern_ = ContactPattern();
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < recording_.contacts.size(); ++k) {
    load_step(k);
    bound = std::min(bound, system_.explicit_stability_bound_s(max_temperature_K));
  }
  return bound;
}

void ThermalReplay::run(thermal::ThermalIntegrator& integrator, std::span<const double> T0_K,
                        const std::string& coupling) {
  pattern_ = ContactPattern();
  edges_.clear_edges();
  system_.replace_edges(edges_);
  integrator.initialize(0.0, T0_K, 0.0);
  for (std::size_t k = 0; k < recording_.step_end_s.size(); ++k) {
    const auto shape_before = system_.topology_version();
    load_step(k);
    if (coupling == "restart" && system_.topology_version() == shape_before) integrator.restart();
    integrator.advance_to(recording_.step_end_s[k]);
  }
}

}  // namespace tmdem::coupling
