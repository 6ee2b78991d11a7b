#include "thermal/IntegratorRegistry.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "thermal/CvodeIntegrator.h"
#include "thermal/ExplicitIntegrator.h"
#include "thermal/IdaIntegrator.h"

namespace tmdem::thermal {

namespace {
std::string join(const std::vector<std::string_view>& names) {
  std::string out;
  for (auto n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}
}  // namespace

std::vector<std::string_view> thermal_integrator_names() { return {"cvode", "ida", "explicit"}; }
std::vector<std::string_view> linear_solver_names() { return {"klu", "pcg"}; }

std::unique_ptr<ThermalIntegrator> make_thermal_integrator(std::string_view name,
                                                           ThermalSystem& system,
                                                           const IntegratorSettings& settings) {
  const auto solvers = linear_solver_names();
  if (std::find(solvers.begin(), solvers.end(), settings.linear_solver) == solvers.end())
    throw std::invalid_argument("unknown linear solver \"" + settings.linear_solver +
                                "\"; valid types are: " + join(solvers));
  if (name == "cvode") return std::make_unique<CvodeIntegrator>(system, settings);
  if (name == "ida") return std::make_unique<IdaIntegrator>(system, settings);
  if (name == "explicit") return std::make_unique<ExplicitIntegrator>(system, settings);
  throw std::invalid_argument("unknown thermal integrator \"" + std::string(name) +
                              "\"; valid types are: " + join(thermal_integrator_names()));
}

}  // namespace tmdem::thermal
