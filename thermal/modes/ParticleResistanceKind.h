#pragma once
// thermal.particle_resistance, parsed once where the scene is read (ParticleResistance.h is the
// model): "off", the particles conduct as their surfaces; "isothermal_core", each shell in
// series with the summed pair conductance of every pair; "isothermal_core_rays", the same for
// the contacts while the surrounding layer's gas crosses the shells ray by ray.
#include <array>
#include <string_view>

#include "thermal/network/KindName.h"

namespace tmdem::thermal {

enum class ParticleResistanceKind { Off, IsothermalCore, IsothermalCoreRays };
// The names, in the enum's order: the one list (the scene schema's choices take it).
inline constexpr std::array<std::string_view, 3> kParticleResistanceNames{
    "off", "isothermal_core", "isothermal_core_rays"};

// An unknown name throws std::invalid_argument listing the valid names.
inline ParticleResistanceKind parse_particle_resistance(std::string_view name) {
  return parse_kind<ParticleResistanceKind>(name, kParticleResistanceNames, "particle resistance");
}
constexpr std::string_view name_of(ParticleResistanceKind kind) {
  return kind_name(kind, kParticleResistanceNames);
}

}  // namespace tmdem::thermal
