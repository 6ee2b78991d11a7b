#include "coupling/scene/HeatModes.h"

#include <algorithm>

#include "thermal/ModeRegistry.h"

namespace tmdem::coupling {

bool switched_on(const Effects& effects, const thermal::ModeDescription& mode) {
  return mode.effect.empty() || effects.on(mode.effect);
}

bool contacts_carry_heat(const Effects& effects) {
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode->uses_contact_conductance && switched_on(effects, *mode)) return true;
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
