#pragma once
// Run-time selection of heat-transfer modes by name (LAMMPS/OpenFOAM style).
#include <memory>
#include <string_view>
#include <vector>

#include "thermal/HeatTransferMode.h"

namespace tmdem::thermal {

// Builds the mode registered under `name`; an unknown name throws std::invalid_argument whose
// message lists the valid names.
std::unique_ptr<HeatTransferMode> make_heat_transfer_mode(std::string_view name,
                                                          const ModeSettings& settings);
std::vector<std::string_view> heat_transfer_mode_names();

// How many modes have been constructed since start, per name: lets tests prove that a mode
// the scene leaves off is never built.
int heat_transfer_mode_constructions(std::string_view name);

}  // namespace tmdem::thermal
