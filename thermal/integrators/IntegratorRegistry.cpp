#include "thermal/integrators/IntegratorRegistry.h"

#include <stdexcept>
#include <string>

#include "thermal/integrators/CvodeIntegrator.h"
#include "thermal/integrators/ExplicitIntegrator.h"
#include "thermal/integrators/IdaIntegrator.h"
#include "thermal/integrators/IntegratorKind.h"

namespace tmdem::thermal {

std::vector<std::string_view> thermal_integrator_names() {
  return {kIntegratorNames.begin(), kIntegratorNames.end()};
}
std::vector<std::string_view> linear_solver_names() {
  return {kLinearSolverNames.begin(), kLinearSolverNames.end()};
}

std::unique_ptr<ThermalIntegrator> make_thermal_integrator(std::string_view name,
                                                           ThermalSystem& system,
                                                           const IntegratorSettings& settings) {
  switch (parse_integrator_kind(name)) {
    case IntegratorKind::Cvode: return std::make_unique<CvodeIntegrator>(system, settings);
    case IntegratorKind::Ida: return std::make_unique<IdaIntegrator>(system, settings);
    case IntegratorKind::Explicit: return std::make_unique<ExplicitIntegrator>(system, settings);
  }
  throw std::logic_error("unhandled thermal integrator kind");
}

}  // namespace tmdem::thermal
