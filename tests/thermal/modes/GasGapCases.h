#pragma once
// The gas-gap cases the gas-conduction tests share (test_gas_gap, test_gas_conduction_mode,
// test_gas_share): sphere radius, layer fraction and minimum gap, and gaps between two spheres
// or a sphere and a plane.
#include <limits>
#include <numbers>

#include "thermal/modes/GasGapConductance.h"

namespace tmdem::thermal::gas_test {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline GasGap spheres(double Ra, double Rb, double gap, double a = 0.0) { return {Ra, Rb, gap, a}; }
inline GasGap plane(double R, double gap, double a = 0.0) { return {R, kInf, gap, a}; }

inline constexpr double kR = 1e-3, kLayer = 0.4, kL = 1e-7;

}  // namespace tmdem::thermal::gas_test
