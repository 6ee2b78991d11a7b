#include "coupling/bridge/DynamicNetwork.h"

namespace tmdem::coupling {

DynamicNetwork::DynamicNetwork(const Scene& scene, thermal::ThermalSystem& system)
    : system_(system), builder_(scene) {}

void DynamicNetwork::reset() {
  pattern_ = ContactPattern();
  edges_.clear_edges();
  system_.replace_edges(edges_);
}

void DynamicNetwork::load(const ContactList& active) {
  pattern_.update(active, pattern_contacts_, pattern_active_);
  builder_.build_edges(pattern_contacts_, edges_, &pattern_active_);
  system_.replace_edges(edges_);
}

void DynamicNetwork::update(ContactList& active, thermal::ThermalIntegrator& integrator,
                            CouplingStrategy coupling) {
  const auto shape_before = system_.topology_version();
  load(active);
  // The output lists the active contacts only; their conductances come from the pattern list
  // (both sorted by pair).
  std::size_t p = 0;
  for (std::size_t c = 0; c < active.size(); ++c) {
    const std::pair key(active.pair[2 * c], active.pair[2 * c + 1]);
    while (std::pair(pattern_contacts_.pair[2 * p], pattern_contacts_.pair[2 * p + 1]) != key) ++p;
    active.conductance_W_per_K[c] = pattern_contacts_.conductance_W_per_K[p];
  }
  // A new shape re-initialises inside advance_to anyway; "restart" also does it otherwise.
  if (coupling == CouplingStrategy::Restart && system_.topology_version() == shape_before) integrator.restart();
}

}  // namespace tmdem::coupling
