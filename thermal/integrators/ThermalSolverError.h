#pragma once
// A thermal integrator failed (CVODE/IDA error code, step refused). Carries the figures a user
// needs to act: the solver's return code and message, the time reached and the last step size.
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

struct ThermalSolverError : std::runtime_error {
  ThermalSolverError(const std::string& message, int code = 0, double time_s = 0.0)
      : std::runtime_error(message), code(code), time_s(time_s) {}
  // "<solver> failed in <call> with <flag name> (<flag>) at t = ... s, step size ... s after ...
  // steps: <detail>" (steps < 0: no step figures; empty detail: none). Frees flag_name (the
  // SUNDIALS *GetReturnFlagName result).
  static ThermalSolverError from_solver(const std::string& solver, char* flag_name, int flag,
                                        const char* call, double t_s, double step_s, long steps,
                                        const std::string& detail) {
    std::ostringstream msg;
    msg << solver << " failed in " << call << " with " << (flag_name ? flag_name : "?") << " ("
        << flag << ") at t = " << t_s << " s";
    std::free(flag_name);
    if (steps >= 0) msg << ", step size " << step_s << " s after " << steps << " steps";
    if (!detail.empty()) msg << ": " << detail;
    return ThermalSolverError(msg.str(), flag, t_s);
  }
  int code;       // solver return flag (negative for SUNDIALS failures), 0 if not from a solver
  double time_s;  // simulated time reached when it failed
};

}  // namespace tmdem::thermal
