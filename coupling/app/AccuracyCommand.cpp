#include "coupling/app/AccuracyCommand.h"

#include <csignal>
#include <optional>


#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/app/StudyCsvFile.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/HeatModes.h"
#include "coupling/studies/AccuracyReport.h"
#include "coupling/studies/ContactRecording.h"
#include "coupling/studies/ThermalReplay.h"

namespace tmdem::coupling {

namespace {

// The study itself (the scene's thermal problem, or a dynamic scene's recorded contacts
// replayed), into `result`; an exit code, kExitOk to go on.
int compute_accuracy_study(const Scene& scene, const AccuracyCommandOptions& options,
                           std::ostream& log, AccuracyStudyResult& result) {
  ProgressReporter progress(log, options.quiet, options.terminal);
  // The scene's solver resolved on its system (a study runs in one process). The study's
  // methods name their own; this one is what the explicit rungs' settings carry.
  auto base_for = [&](const thermal::ThermalSystem& system) {
    return integrator_settings(scene, choose_linear_solver(scene, system, 1).kind);
  };
  if (scene.effects.mechanics == MechanicsMode::Coupled) {
    log << "error: tmdem study accuracy takes scenes with effects.mechanics = \"off\", "
           "\"settle\" or \"dynamic\"; a \"coupled\" scene's network changes with its "
           "temperatures, which differ between the study's runs\n";
    return kExitInvalid;
  }
  if (scene.effects.mechanics == MechanicsMode::Dynamic && near_pair_reach(scene) > 0.0) {
    log << "error: tmdem study accuracy replays a dynamic scene's recorded contacts without "
           "positions, so it cannot follow the near pairs of effects.gas_conduction or "
           "[radiation] between_particles; switch them off or use \"settle\"\n";
    return kExitInvalid;
  }
  if (scene.effects.mechanics == MechanicsMode::Dynamic) {
    // Record the mechanics once; every run replays the same contact graph.
    const auto recording = record_contacts(scene, progress);
    ContactList no_contacts;
    auto system = build_thermal_system(scene, no_contacts);
    const auto base = base_for(*system);
    std::vector<double> T0;
    for (const auto& p : scene.particles) T0.push_back(p.temperature_K);
    ThermalReplay replay(scene, recording, *system);
    auto study = options.study;
    study.stability_bound_s = replay.min_stability_bound_s(base.max_temperature_K);
    study.max_explicit_step_s = scene.mechanics.time_step_s;
    const ThermalDriver driver = [&](thermal::ThermalIntegrator& integ, std::span<const double> T,
                                     double, CouplingStrategy coupling) {
      replay.run(integ, T, coupling);
    };
    result = run_accuracy_study(*system, T0, scene.duration_s, base, study,
                                options.quiet ? nullptr : &log, driver);
  } else {
    auto problem = build_frozen_thermal_problem(scene, progress);
    result = run_accuracy_study(*problem.system, problem.T0_K, scene.duration_s,
                                base_for(*problem.system),
                                options.study, options.quiet ? nullptr : &log);
  }
  return kExitOk;
}

}  // namespace

int run_accuracy_command(const Scene& scene, const AccuracyCommandOptions& options,
                         std::ostream& out, std::ostream& log) {
  // Open the CSVs first: an unwritable path should fail before minutes of computation. The
  // runs skipped as too slow go beside the study's table (OUT.skipped.csv): every row of the
  // contract's table is a run made.
  StudyCsvFile csv(options.csv_path);
  StudyCsvFile skipped_csv(options.csv_path.empty() ? "" : skipped_runs_csv_path(options.csv_path));
  if (!csv.open(log)) return kExitIo;
  if (!skipped_csv.open(log)) {
    csv.discard();
    return kExitIo;
  }

  std::optional<Interruption> interruption;
  AccuracyCommandOptions study_options = options;
  if (options.handle_signals) {
    interruption.emplace(options.quiet,
                         "\ninterrupt received: finishing the current run, then reporting and "
                         "writing the runs made; a second signal, a second or more later, aborts at once\n");
    study_options.study.stop = &Interruption::requested;
  }
  AccuracyStudyResult result;
  // A failure removes both files (no half table).
  const int computed = csv.compute_or_discard<ReferenceError>([&] {
    return skipped_csv.compute_or_discard<ReferenceError>(
        [&] { return compute_accuracy_study(scene, study_options, log, result); }, log);
  }, log);
  if (computed != kExitOk) return computed;
  for (const auto& r : result.runs)
    if (r.failed())
      log << "warning: " << r.label() << " "
          << (r.is_explicit() ? "h = " : "rtol = ") << shortest_number(r.parameter)
          << " failed (left out of the CSV): " << r.message << std::endl;

  out << "accuracy study: " << scene.source << "\n";
  print_accuracy_report(out, result, options.study);
  out.flush();

  const bool written =
      csv.write([&](std::ostream& f) { write_accuracy_csv(f, result.runs); }, log, options.quiet) &&
      skipped_csv.write([&](std::ostream& f) { write_skipped_runs_csv(f, result.runs); }, log, options.quiet);
  if (!written) return kExitIo;
  // Interrupted: the study reported and wrote what it made, as a complete one would.
  if (const int signal = Interruption::pending(); signal != 0 && options.handle_signals) {
    std::size_t made = 0, not_made = 0;
    for (const auto& r : result.runs) {
      if (r.ok) ++made;
      if (r.skipped && r.message == kInterruptedRunReason) ++not_made;
    }
    log << "interrupted by " << signal_name(signal) << ": " << made << " runs made, " << not_made
        << " not made" << (options.csv_path.empty() ? std::string()
                                                    : " (listed in " + skipped_runs_csv_path(options.csv_path) + ")")
        << std::endl;
    return signal == SIGINT ? kExitSigint : kExitSigterm;
  }
  return kExitOk;
}

}  // namespace tmdem::coupling
