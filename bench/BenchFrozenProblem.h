#pragma once
// What the in-process benchmarks of whole thermal runs share: the scene's frozen thermal
// problem built as `tmdem run` builds it (progress discarded), the integrator settings at the
// scene's linear solver ("auto" resolved for one process), and the process's CPU time.
#include <ctime>
#include <sstream>

#include "coupling/output/ProgressReporter.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"

namespace tmdem::bench {

inline double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

inline coupling::FrozenThermalProblem quiet_frozen_problem(const coupling::Scene& scene) {
  std::ostringstream quiet;
  coupling::ProgressReporter progress(quiet, true, false);
  return coupling::build_frozen_thermal_problem(scene, progress);
}

inline thermal::IntegratorSettings settings_for(const coupling::Scene& scene,
                                                const thermal::ThermalSystem& system) {
  return coupling::integrator_settings(scene, coupling::choose_linear_solver(scene, system, 1).kind);
}

}  // namespace tmdem::bench
