#pragma once
// A thermal integrator failed (CVODE/IDA error code, step refused). Carries the figures a user
// needs to act: the solver's return code and message, the time reached and the last step size.
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

struct ThermalSolverError : std::runtime_error {
  ThermalSolverError(const std::string& message, int code = 0, double time_s = 0.0)
      : std::runtime_error(message), code(code), time_s(time_s) {}
  int code;       // solver return flag (negative for SUNDIALS failures), 0 if not from a solver
  double time_s;  // simulated time reached when it failed
};

}  // namespace tmdem::thermal
