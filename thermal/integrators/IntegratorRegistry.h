#pragma once
// Run-time selection of thermal integrators by name.
#include <memory>
#include <string_view>
#include <vector>

#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::thermal {

// Unknown names (integrator or linear solver) throw std::invalid_argument listing valid names.
std::unique_ptr<ThermalIntegrator> make_thermal_integrator(std::string_view name,
                                                           ThermalSystem& system,
                                                           const IntegratorSettings& settings);
std::vector<std::string_view> thermal_integrator_names();
std::vector<std::string_view> linear_solver_names();

}  // namespace tmdem::thermal
