#include "coupling/app/ConductivityCommand.h"


#include <csignal>
#include <optional>
#include <tuple>

#include "coupling/app/StudyCsvFile.h"
#include "coupling/common/ExitCode.h"
#include "coupling/common/ShortestNumber.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/run/MechanicsStepLog.h"
#include "coupling/run/Interruption.h"
#include "coupling/studies/ConductivityReport.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::coupling {

int run_conductivity_command(const Scene& scene, const ConductivityCommandOptions& options,
                             std::ostream& out, std::ostream& log) {
  if (!options.step_log_path.empty() && options.step_log_path == options.csv_path) {
    log << "error: step log '" << options.step_log_path << "' is the CSV file; choose another --step-log" << std::endl;
    return kExitInvalid;
  }
  StudyCsvFile csv(options.csv_path);
  if (!csv.open(log)) return kExitIo;
  std::optional<MechanicsStepLog> step_log;
  try {
    if (!options.step_log_path.empty()) step_log.emplace(options.step_log_path, false);
  } catch (const OutputError& e) {
    log << "error: " << e.what() << std::endl;
    csv.discard();
    return kExitIo;
  }
  MechanicsStepLog* const steps = step_log ? &*step_log : nullptr;

  // A study of one load has nothing to keep: a signal ends it at once, as by default.
  std::optional<Interruption> interruption;
  if (options.handle_signals && !options.pressures_Pa.empty())
    interruption.emplace(options.quiet,
                         "\ninterrupt received: giving up the current settle step, then reporting "
                         "and writing the loads finished; a second signal, a second or more later, aborts at once\n",
                         true);
  std::vector<ConductivityResult> results;
  const int computed = csv.compute_or_discard<thermal::ThermalSolverError>([&] {
    ProgressReporter progress(log, options.quiet, options.terminal);
    if (options.pressures_Pa.empty())
      results.push_back(run_conductivity_study(scene, progress, steps));
    else
      results = run_conductivity_pressure_study(scene, options.pressures_Pa, progress,
                                                &Interruption::requested, steps);
    return kExitOk;
  }, log);
  if (computed != kExitOk) return computed;
  // Interrupted: the loads finished are reported and written as a complete study's would be.
  const int signal = Interruption::pending();
  const bool stopped_early = signal != 0 && !options.pressures_Pa.empty() &&
                             results.size() < options.pressures_Pa.size();
  out << "conductivity study: " << scene.source << "\n";
  for (const auto& r : results) print_conductivity_report(out, r);
  out.flush();
  for (const auto& r : results)
    for (const auto& [wall, count, side] :
         {std::tuple{r.hot_wall, r.hot_wall_contacts, "hot"}, std::tuple{r.cold_wall, r.cold_wall_contacts, "cold"}})
      if (count == 0)
        log << "warning: the " << side << " wall[" << wall
            << "] touches no particle, so no heat crosses the bed (k_eff = 0): place it where the "
               "bed ends, or make it a piston (piston = true) that presses onto the bed"
            << std::endl;
  for (const auto& r : results)
    if (!r.at_rest)
      log << "warning: the bed" << (r.pressure_Pa ? " at " + shortest_number(*r.pressure_Pa) + " Pa" : std::string())
          << " was not at rest after mechanics.settle_time; k_eff is that of the packing as it was"
          << std::endl;
  for (const auto& r : results)
    if (r.balance_rel > 1e-9)
      log << "warning: heat in (" << r.heat_hot_W << " W) and heat out (" << r.heat_cold_W
          << " W) differ by " << r.balance_rel
          << " relative: some mode exchanges heat with the surroundings, a source or a held "
             "particle (a bed enclosed between the two walls radiates to nothing else: "
             "[radiation] surroundings = false)" << std::endl;

  const bool written =
      csv.write([&](std::ostream& f) { write_conductivity_csv(f, results); }, log, options.quiet);
  if (!written) return kExitIo;
  if (!stopped_early) return kExitOk;
  log << "interrupted by " << signal_name(signal) << " after " << results.size() << " of "
      << options.pressures_Pa.size() << " loads; "
      << (options.csv_path.empty() ? std::string("the report above holds")
                                   : "the report above and " + options.csv_path + " hold")
      << " the loads finished" << std::endl;
  return signal == SIGINT ? kExitSigint : kExitSigterm;
}

}  // namespace tmdem::coupling
