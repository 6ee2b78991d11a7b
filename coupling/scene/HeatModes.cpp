#include "coupling/scene/HeatModes.h"

#include <algorithm>

#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

bool switched_on(const Effects& effects, const thermal::ModeDescription& mode) {
  return mode.effect.empty() || effects.on(mode.effect);
}

bool mode_enabled(const Scene& scene, const thermal::ModeDescription& mode) {
  if (!switched_on(scene.effects, mode)) return false;
  if (mode.enabled_by.empty()) return true;
  return thermal::resolve_mode_parameters(mode, scene.heat_modes)[mode.enabled_by] != 0.0;
}

double near_pair_reach(const Scene& scene) {
  double reach = 0.0;
  for (const auto* mode : thermal::heat_transfer_modes())
    if (!mode->near_pair_reach.empty() && mode_enabled(scene, *mode))
      reach = std::max(reach, thermal::resolve_mode_parameters(*mode, scene.heat_modes)[mode->near_pair_reach]);
  return reach;
}

bool needs_line_of_sight(const Scene& scene) {
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode->needs_line_of_sight && mode_enabled(scene, *mode)) return true;
  return false;
}

bool contacts_carry_heat(const Effects& effects) {
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode->uses_contact_conductance && switched_on(effects, *mode)) return true;
  return false;
}

bool contacts_dissipate_heat(const Effects& effects) {
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode->uses_contact_dissipation && switched_on(effects, *mode)) return true;
  return false;
}

double max_mode_temperature_K(const Scene& scene) {
  double T_max = 0.0;
  for (const auto* mode : thermal::heat_transfer_modes()) {
    if (!switched_on(scene.effects, *mode)) continue;
    const auto values = thermal::resolve_mode_parameters(*mode, scene.heat_modes);
    for (const auto& p : mode->parameters)
      if (p.bounds_temperature) T_max = std::max(T_max, values[p.key]);
  }
  return T_max;
}

}  // namespace tmdem::coupling
