#pragma once
// Run-time selection of heat-transfer modes by name (LAMMPS/OpenFOAM style). Each mode declares
// itself in its own file (thermal/modes/ModeDescription.h); the built-in modes are listed one line
// each in thermal/modes/ModeList.h, and a program may register more before it reads a scene (the
// test-only fault_injection mode is registered this way, never by the production binary).
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "thermal/modes/HeatTransferMode.h"
#include "thermal/modes/ModeDescription.h"
#include "thermal/modes/ModeSettings.h"

namespace tmdem::thermal {

// Every registered mode in registration order, which is also the order their heat flows are
// summed: the built-in list first, then the modes registered at run time.
const std::vector<const ModeDescription*>& heat_transfer_modes();
const ModeDescription* find_heat_transfer_mode(std::string_view name);
std::vector<std::string_view> heat_transfer_mode_names();

// Adds a mode (kept by reference: it must outlive the program's use of the registry). Throws
// std::invalid_argument for a name already taken, or an effect key another mode declares with
// another default. Call before reading any scene.
void register_heat_transfer_mode(const ModeDescription& mode);
// Changes with every registration, so caches built from the registry (the scene schema) can
// tell they are stale.
std::uint64_t heat_transfer_registry_version();

// The effects.<key> switches the modes declare, each once, in registration order.
struct EffectSwitch {
  std::string_view key;
  bool default_on = false;
  std::string_view description;
};
std::vector<EffectSwitch> heat_transfer_effects();

// `mode`'s parameters from `settings`, declared defaults for the unset ones, checked: a key the
// mode does not declare, a value outside its range or a failed mode check throws
// std::invalid_argument naming mode.key and what is allowed.
ModeParameters resolve_mode_parameters(const ModeDescription& mode, const ModeSettings& settings);

// Builds the mode registered under `name`; an unknown name throws std::invalid_argument whose
// message lists the valid names.
std::unique_ptr<HeatTransferMode> make_heat_transfer_mode(std::string_view name,
                                                          const ModeSettings& settings);

// How many modes have been constructed since start, per name: lets tests prove that a mode
// the scene leaves off is never built.
int heat_transfer_mode_constructions(std::string_view name);

}  // namespace tmdem::thermal
