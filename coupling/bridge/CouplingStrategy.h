#pragma once
// How the thermal integrator follows a dynamic packing (scene key thermal.coupling), parsed once
// from the scene's name so the step loop compares an enum, not a string.
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tmdem::coupling {

enum class CouplingStrategy {
  Continue,  // keep the BDF history while contacts only change force
  Restart,   // re-initialise the integrator at every mechanical step
};

inline constexpr std::array<std::string_view, 2> kCouplingStrategyNames{"continue", "restart"};

constexpr std::string_view name_of(CouplingStrategy s) {
  return kCouplingStrategyNames[static_cast<int>(s)];
}

// Unknown names throw std::invalid_argument listing the valid ones (the scene schema refuses
// them first, so this only fires for names built in code).
inline CouplingStrategy parse_coupling_strategy(std::string_view name) {
  for (std::size_t i = 0; i < kCouplingStrategyNames.size(); ++i)
    if (kCouplingStrategyNames[i] == name) return static_cast<CouplingStrategy>(i);
  throw std::invalid_argument("unknown thermal.coupling \"" + std::string(name) +
                              "\"; valid types are: continue, restart");
}

}  // namespace tmdem::coupling
