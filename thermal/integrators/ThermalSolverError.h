#pragma once
// A thermal integrator failed (CVODE/IDA error code, step refused). Carries the figures a user
// needs to act: the solver's return code and message, the time reached and the last step size.
#include <cstddef>
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

// What a failed KLU factorisation (CVODE/IDA's linear-solver setup failing unrecoverably with
// thermal.linear_solver = "klu") means and what to choose instead, from KLU's status
// (klu_common::status, klu.h: 1 singular, -2 out of memory, -4 integer overflow); the
// CVODE/IDA flag alone ("the setup routine failed in an unrecoverable manner") names neither.
// `unknowns`: the matrix's size; `symmetric_jacobian`: whether pcg and amg could take it.
inline std::string klu_failure_hint(int klu_status, std::size_t unknowns, bool symmetric_jacobian) {
  std::ostringstream msg;
  msg << "the sparse LU factorisation (KLU) of the " << unknowns
      << "-unknown Newton matrix failed (";
  switch (klu_status) {
    case 1: msg << "singular matrix"; break;
    case -2:
      msg << "out of memory: the LU factors' fill-in grows far faster than the network";
      break;
    case -4: msg << "too large: the LU factors' size overflows an integer"; break;
    default: msg << "out of memory or singular; KLU status " << klu_status; break;
  }
  msg << "); ";
  if (symmetric_jacobian)
    msg << "set thermal.linear_solver = \"amg\" or \"pcg\" (conjugate gradients, memory linear "
           "in the bed), or leave it out: \"auto\" chooses by size (valid values: \"auto\", "
           "\"klu\", \"pcg\", \"amg\")";
  else
    msg << "pcg and amg cannot take this Jacobian (temperature-dependent properties or "
           "particle-particle radiation make it one-sided): only thermal.linear_solver = "
           "\"klu\" can, so make the bed smaller or those properties constant";
  return msg.str();
}

}  // namespace tmdem::thermal
