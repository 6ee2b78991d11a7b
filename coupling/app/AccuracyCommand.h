#pragma once
// `tmdem study accuracy`: the study (studies/AccuracyStudy.h) run on a loaded scene, with its
// report and CSV (studies/AccuracyReport.h).
#include <ostream>
#include <string>

#include "coupling/scene/Scene.h"
#include "coupling/studies/AccuracyStudy.h"

namespace tmdem::coupling {

// The whole subcommand on a loaded scene: frozen problem (mechanics off or settle) or, for a
// dynamic scene, the recorded contact graph replayed for every run (reference: CVODE/KLU
// restarted every mechanical step at rtol 1e-12); then the study, the CSV (csv_path empty:
// none), the report on `out`, progress and errors on `log`. Returns the exit code: 0 ok,
// 3 the reference failed, 4 the CSV cannot be written.
struct AccuracyCommandOptions {
  std::string csv_path;
  bool quiet = false;
  bool terminal = false;
  // SIGINT/SIGTERM end the study after the current run: the runs made are reported and written
  // (the others listed as skipped: "the study was interrupted"), exit 130/143.
  bool handle_signals = false;
  AccuracyStudyOptions study;
};
int run_accuracy_command(const Scene& scene, const AccuracyCommandOptions& options,
                         std::ostream& out, std::ostream& log);

}  // namespace tmdem::coupling
