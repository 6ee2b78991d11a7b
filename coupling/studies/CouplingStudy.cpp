#include "coupling/studies/CouplingStudy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "coupling/studies/ContactRecording.h"
#include "coupling/common/ExitCode.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/HeatModes.h"
#include "coupling/studies/ThermalReplay.h"
#include "thermal/integrators/IntegratorRegistry.h"

namespace tmdem::coupling {

namespace {

struct Variant {
  CouplingStrategy strategy;
  thermal::IntegratorKind integrator;  // cvode, or explicit at the mechanical step
  double parameter;                    // rtol, or the explicit step (s)

  // The CSV's strategy column: continue | restart | explicit.
  std::string strategy_name() const {
    return std::string(integrator == thermal::IntegratorKind::Explicit ? thermal::name_of(integrator)
                                                                       : name_of(strategy));
  }
  std::string integrator_name() const { return std::string(thermal::name_of(integrator)); }
};

struct Row {
  Variant v;
  double max_error_K = 0.0;
  double thermal_wall_s = 0.0;
  thermal::IntegratorStats stats;
  std::vector<double> T;
  std::string failure;
};

Row run_variant(const Scene& scene, thermal::ThermalSystem& system, ThermalReplay& replay,
                const std::vector<double>& T0, const Variant& v) {
  // KLU whatever the scene says: the study compares strategies, not linear solvers.
  auto s = integrator_settings(scene, thermal::LinearSolverKind::Klu);
  s.stop_at_each_time = true;
  if (v.integrator == thermal::IntegratorKind::Explicit) {
    s.explicit_step_s = v.parameter;
  } else {
    s.relative_tolerance = v.parameter;
    s.absolute_tolerance_K = v.parameter;
  }
  Row row;
  row.v = v;
  try {
    auto integrator = thermal::make_thermal_integrator(thermal::name_of(v.integrator), system, s);
    const auto start = std::chrono::steady_clock::now();
    replay.run(*integrator, T0, v.strategy);
    row.thermal_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    row.stats = integrator->stats();
    const auto T = integrator->temperatures_K();
    row.T.assign(T.begin(), T.end());
  } catch (const std::exception& e) {
    row.failure = e.what();
  }
  return row;
}

}  // namespace

int run_coupling_study(const Scene& scene, const std::string& csv_path, std::ostream& out,
                       std::ostream& log) {
  if (scene.effects.mechanics != MechanicsMode::Dynamic) {
    log << "error: tmdem study coupling needs a scene with effects.mechanics = \"dynamic\"\n";
    return kExitInvalid;
  }
  if (near_pair_reach(scene) > 0.0) {  // replays know contacts, not positions
    log << "error: tmdem study coupling replays recorded contacts without positions, so it cannot "
           "follow the near pairs of effects.gas_conduction or [radiation] between_particles; "
           "switch them off for the study\n";
    return kExitInvalid;
  }
  const double h = scene.mechanics.time_step_s;
  ProgressReporter progress(log, false, false);
  const auto recording = record_contacts(scene, progress);
  out << "coupling study: " << scene.source << ", " << scene.particles.size() << " particles, "
      << scene.duration_s << " s at mechanical step " << h << " s (mechanics recorded once, "
      << recording.mechanics_wall_time_s << " s, and replayed for every variant)\n";

  ContactList no_contacts;
  auto system = build_thermal_system(scene, no_contacts);
  std::vector<double> T0;
  for (const auto& p : scene.particles) T0.push_back(p.temperature_K);
  ThermalReplay replay(scene, recording, *system);

  const auto ref = run_variant(scene, *system, replay, T0, {CouplingStrategy::Restart, thermal::IntegratorKind::Cvode, 1e-12});
  if (!ref.failure.empty()) {
    log << "error: the reference run failed: " << ref.failure << "\n";
    return kExitSolverFailed;
  }
  out << "reference: cvode/klu restarted every mechanical step, rtol = atol = 1e-12 ("
      << ref.stats.steps << " thermal steps, " << ref.thermal_wall_s << " s)\n";

  using thermal::IntegratorKind;
  const auto cont = CouplingStrategy::Continue, restart = CouplingStrategy::Restart;
  const std::vector<Variant> variants{
      {cont, IntegratorKind::Cvode, 1e-4},    {cont, IntegratorKind::Cvode, 1e-6},
      {cont, IntegratorKind::Cvode, 1e-8},    {restart, IntegratorKind::Cvode, 1e-4},
      {restart, IntegratorKind::Cvode, 1e-6}, {restart, IntegratorKind::Cvode, 1e-8},
      {cont, IntegratorKind::Explicit, h}};
  std::ostringstream csv;
  csv << "strategy,integrator,parameter,max_error_K,thermal_wall_time_s,thermal_steps,"
         "reinitializations\n";
  out << std::left << std::setw(10) << "strategy" << std::setw(10) << "integ" << std::setw(11)
      << "parameter" << std::setw(13) << "max_error_K" << std::setw(12) << "thermal_s"
      << std::setw(10) << "steps" << "reinits\n";
  for (const auto& v : variants) {
    auto row = run_variant(scene, *system, replay, T0, v);
    if (!row.failure.empty()) {
      log << "warning: " << v.strategy_name() << " (" << v.parameter << ") failed: " << row.failure << "\n";
      out << std::left << std::setw(10) << v.strategy_name() << std::setw(10) << v.integrator_name()
          << std::setw(11) << v.parameter << "FAILED (left out of the CSV)\n";
      continue;
    }
    for (std::size_t i = 0; i < ref.T.size(); ++i)
      row.max_error_K = std::max(row.max_error_K, std::abs(row.T[i] - ref.T[i]));
    csv << v.strategy_name() << "," << v.integrator_name() << "," << v.parameter << "," << row.max_error_K << ","
        << row.thermal_wall_s << "," << row.stats.steps << "," << row.stats.reinitializations << "\n";
    out << std::left << std::setw(10) << v.strategy_name() << std::setw(10) << v.integrator_name() << std::setw(11)
        << v.parameter << std::setw(13) << row.max_error_K << std::setw(12) << row.thermal_wall_s
        << std::setw(10) << row.stats.steps << row.stats.reinitializations << "\n";
  }
  if (!csv_path.empty()) {
    std::ofstream f(csv_path);
    f << csv.str();
    if (!f) {
      log << "error: cannot write " << csv_path << "\n";
      return kExitIo;
    }
  }
  return kExitOk;
}

}  // namespace tmdem::coupling
