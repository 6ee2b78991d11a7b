#pragma once
// What every stability case asserts: the run finishes, no NaN, the maximum principle holds
// (temperatures stay inside the range of the initial and boundary temperatures) and the energy
// balance closes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::stability {

using thermal::IntegratorSettings;
using thermal::ThermalNetwork;
using thermal::ThermalSystem;

inline std::unique_ptr<ThermalSystem> make_system(const ThermalNetwork& net,
                                                  const std::vector<std::string>& modes,
                                                  const thermal::ModeSettings& settings = {}) {
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> built;
  for (const auto& m : modes) built.push_back(thermal::make_heat_transfer_mode(m, settings));
  return std::make_unique<ThermalSystem>(net, std::move(built));
}

struct Bounds {
  double low_K, high_K;
};

// Advances to each of `times`, checking the invariants after every one.
inline void run_and_check(ThermalSystem& sys, const std::string& integrator,
                          const IntegratorSettings& s, const std::vector<double>& T0,
                          const std::vector<double>& times, Bounds bounds,
                          double balance_tolerance) {
  auto integ = thermal::make_thermal_integrator(integrator, sys, s);
  integ->initialize(0.0, T0, 0.0);
  const double E0 = sys.thermal_energy_J(T0);
  for (double t : times) {
    ASSERT_NO_THROW(integ->advance_to(t)) << integrator << " at t = " << t;
    const auto T = integ->temperatures_K();
    for (std::size_t i = 0; i < T.size(); ++i) {
      ASSERT_TRUE(std::isfinite(T[i])) << "particle " << i << " at t = " << t;
      const double slack = 1e-6 * (bounds.high_K - bounds.low_K);
      ASSERT_GE(T[i], bounds.low_K - slack) << "particle " << i << " at t = " << t;
      ASSERT_LE(T[i], bounds.high_K + slack) << "particle " << i << " at t = " << t;
    }
    const double E = sys.thermal_energy_J(T), Q = integ->boundary_heat_J();
    ASSERT_TRUE(std::isfinite(Q));
    const double scale = std::max(std::abs(E0), std::abs(Q));
    EXPECT_LE(std::abs(E - E0 - Q), balance_tolerance * scale) << integrator << " at t = " << t;
  }
}

}  // namespace tmdem::stability
