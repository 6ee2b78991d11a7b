#pragma once
// `tmdem study conductivity SCENE [--pressures P1,P2,...] [--csv OUT]`: prints the effective
// conductivity report (coupling/studies/ConductivityStudy.h) and writes the CSV. Returns the
// exit code.
#include <ostream>
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

struct ConductivityCommandOptions {
  std::string csv_path;
  std::string step_log_path;  // --step-log: a CSV line per settle step (MechanicsStepLog.h); empty: none
  std::vector<double> pressures_Pa;  // empty: the bed as the scene gives it
  bool quiet = false;
  bool terminal = false;
  // SIGINT/SIGTERM end a --pressures study after the current settle step: the loads finished
  // are reported and written, exit 130/143 (a study of one load just stops, exit 130/143).
  bool handle_signals = false;
};

int run_conductivity_command(const Scene& scene, const ConductivityCommandOptions& options,
                             std::ostream& out, std::ostream& log);

}  // namespace tmdem::coupling
