#pragma once
// Hands a moving packing's contacts to the thermal system, one mechanical step at a time, the
// same way for `tmdem run` and for the studies' replays: a sticky contact pattern (open
// contacts keep a zero-conductance edge until a new pair closes), the step's conductances, and
// with thermal.coupling = "restart" a re-initialised integrator every step ("continue": only
// when the step's friction-heat source changed).
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/bridge/ContactPattern.h"
#include "coupling/bridge/CouplingStrategy.h"
#include "coupling/scene/Scene.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

class DynamicNetwork {
 public:
  DynamicNetwork(const Scene& scene, thermal::ThermalSystem& system);

  // No contact, empty pattern (t = 0 of a dynamic run).
  void reset();
  // active: this step's contacts in canonical order; their conductances are filled in, and
  // their dissipated powers handed to the network when a mode reads them (friction heat).
  // geometry: the packing of this step, required when a mode works across gaps (gas, pair
  // radiation): its near pairs then join the sticky pattern like contacts, and every pattern
  // edge carries this step's gap.
  void update(ContactList& active, thermal::ThermalIntegrator& integrator,
              CouplingStrategy coupling, const mechanics::ParticleSet* geometry = nullptr);
  // As update, without an integrator (e.g. to inspect the network of a step).
  void load(const ContactList& active, const mechanics::ParticleSet* geometry = nullptr);

  // The sticky pattern as pairs i, j (checkpoints), and a restart's way back: the pattern as it
  // was, then the network of the checkpoint's active contacts on it (no pattern change).
  std::vector<std::int64_t> pattern_pairs() const;
  void restore(const std::vector<std::int64_t>& pattern_pairs, const ContactList& active,
               const mechanics::ParticleSet* geometry = nullptr);

 private:
  thermal::ThermalSystem& system_;
  ThermalNetworkBuilder builder_;
  ContactPattern pattern_;
  ContactList pattern_contacts_;
  std::vector<std::uint8_t> pattern_active_;
  ContactList with_near_;  // this step's contacts and near pairs, canonical order
  thermal::ThermalNetwork edges_;
  bool dissipation_;  // some switched-on mode turns the contacts' dissipation into heat
  // The previous step's dissipation entries: "continue" restarts the integrator when they change.
  std::vector<std::int32_t> previous_dissipation_a_, previous_dissipation_b_;
  std::vector<double> previous_dissipation_W_;
};

}  // namespace tmdem::coupling
