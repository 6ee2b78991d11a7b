#include "coupling/bridge/DynamicNetwork.h"

#include <stdexcept>

#include "coupling/scene/HeatModes.h"

namespace tmdem::coupling {

DynamicNetwork::DynamicNetwork(const Scene& scene, thermal::ThermalSystem& system)
    : system_(system), builder_(scene), dissipation_(contacts_dissipate_heat(scene.effects)) {}

void DynamicNetwork::reset() {
  pattern_ = ContactPattern();
  edges_.clear_edges();
  system_.replace_edges(edges_);
}

void DynamicNetwork::load(const ContactList& active, const mechanics::ParticleSet* geometry) {
  if (builder_.near_reach() > 0.0) {
    if (geometry == nullptr)
      throw std::invalid_argument(
          "a mode working across gaps (gas conduction, pair radiation) needs the packing's "
          "positions every step; replays of recorded contacts (tmdem study accuracy / coupling "
          "on a dynamic scene) do not have them");
    builder_.add_near_pairs(active, *geometry, with_near_);
    pattern_.update(with_near_, pattern_contacts_, pattern_active_);
    builder_.build_pattern_edges(pattern_contacts_, active, edges_, *geometry);
  } else {
    pattern_.update(active, pattern_contacts_, pattern_active_);
    builder_.build_edges(pattern_contacts_, edges_, &pattern_active_);
  }
  edges_.dissipation_a.clear();
  edges_.dissipation_b.clear();
  edges_.dissipation_W.clear();
  if (dissipation_)
    for (std::size_t c = 0; c < active.size(); ++c) {
      const std::int64_t j = active.pair[2 * c + 1];
      if (active.dissipated_power_W[c] != 0.0)
        edges_.add_dissipation(std::int32_t(active.pair[2 * c]), j >= 0 ? std::int32_t(j) : -1,
                               active.dissipated_power_W[c]);
    }
  system_.replace_edges(edges_);
}

std::vector<std::int64_t> DynamicNetwork::pattern_pairs() const {
  std::vector<std::int64_t> out;
  out.reserve(2 * pattern_.size());
  for (const auto& [i, j] : pattern_.pairs()) {
    out.push_back(i);
    out.push_back(j);
  }
  return out;
}

void DynamicNetwork::restore(const std::vector<std::int64_t>& pattern_pairs, const ContactList& active,
                             const mechanics::ParticleSet* geometry) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (std::size_t p = 0; p + 1 < pattern_pairs.size(); p += 2)
    pairs.emplace_back(pattern_pairs[p], pattern_pairs[p + 1]);
  pattern_.restore(std::move(pairs));
  load(active, geometry);
}

void DynamicNetwork::update(ContactList& active, thermal::ThermalIntegrator& integrator,
                            CouplingStrategy coupling, const mechanics::ParticleSet* geometry) {
  const auto shape_before = system_.topology_version();
  previous_dissipation_a_.swap(edges_.dissipation_a);
  previous_dissipation_b_.swap(edges_.dissipation_b);
  previous_dissipation_W_.swap(edges_.dissipation_W);
  load(active, geometry);
  const bool source_changed = edges_.dissipation_a != previous_dissipation_a_ ||
                              edges_.dissipation_b != previous_dissipation_b_ ||
                              edges_.dissipation_W != previous_dissipation_W_;
  // The output lists the active contacts only; their conductances come from the pattern list
  // (both sorted by pair).
  std::size_t p = 0;
  for (std::size_t c = 0; c < active.size(); ++c) {
    const std::pair key(active.pair[2 * c], active.pair[2 * c + 1]);
    while (std::pair(pattern_contacts_.pair[2 * p], pattern_contacts_.pair[2 * p + 1]) != key) ++p;
    active.conductance_W_per_K[c] = pattern_contacts_.conductance_W_per_K[p];
  }
  // A new shape re-initialises inside advance_to anyway; "restart" also does it otherwise.
  // "continue" does it too when the step's dissipated powers (friction heat) changed: that
  // source is constant over the step and jumps between steps, and a BDF history carried across
  // the jump integrates it wrongly (BDF2: h (P_old - P_new) / 3 per jump; 0.32% of the heat of
  // a slipping sphere was lost so). From a fresh start a constant source integrates exactly.
  const bool restart = coupling == CouplingStrategy::Restart || source_changed;
  if (restart && system_.topology_version() == shape_before) integrator.restart();
}

}  // namespace tmdem::coupling
