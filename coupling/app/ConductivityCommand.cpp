#include "coupling/app/ConductivityCommand.h"


#include <tuple>

#include "coupling/app/StudyCsvFile.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/studies/ConductivityReport.h"
#include "thermal/ThermalSolverError.h"

namespace tmdem::coupling {

int run_conductivity_command(const Scene& scene, const ConductivityCommandOptions& options,
                             std::ostream& out, std::ostream& log) {
  if (!options.pressures_Pa.empty()) {
    // A load needs a plane wall that moves along its normal under an imposed pressure, with
    // its own mass; the mechanics has no such wall yet.
    log << "error: --pressures needs a piston (a plane wall moving along its normal under an "
           "imposed pressure), which tmdem's mechanics does not have yet (issue 12); run "
           "without --pressures for the bed as the scene gives it" << std::endl;
    return kExitInvalid;
  }
  StudyCsvFile csv(options.csv_path);
  if (!csv.open(log)) return kExitIo;

  std::vector<ConductivityResult> results;
  try {
    ProgressReporter progress(log, options.quiet, options.terminal);
    results.push_back(run_conductivity_study(scene, progress));
  } catch (const thermal::ThermalSolverError& e) {
    log << "error: " << e.what() << std::endl;
    csv.discard();
    return kExitSolverFailed;
  } catch (...) {
    csv.discard();
    throw;
  }
  out << "conductivity study: " << scene.source << "\n";
  for (const auto& r : results) print_conductivity_report(out, r);
  out.flush();
  for (const auto& r : results)
    for (const auto& [wall, count, side] :
         {std::tuple{r.hot_wall, r.hot_wall_contacts, "hot"}, std::tuple{r.cold_wall, r.cold_wall_contacts, "cold"}})
      if (count == 0)
        log << "warning: the " << side << " wall[" << wall
            << "] touches no particle, so no heat crosses the bed (k_eff = 0): place it where the "
               "bed ends (a settled bed's top is uneven: a piston that presses the wall onto it "
               "does not exist yet)" << std::endl;
  for (const auto& r : results)
    if (r.balance_rel > 1e-9)
      log << "warning: heat in (" << r.heat_hot_W << " W) and heat out (" << r.heat_cold_W
          << " W) differ by " << r.balance_rel
          << " relative: some mode exchanges heat with the surroundings, a source or a held "
             "particle" << std::endl;

  const bool written =
      csv.write([&](std::ostream& f) { write_conductivity_csv(f, results); }, log, options.quiet);
  return written ? kExitOk : kExitIo;
}

}  // namespace tmdem::coupling
