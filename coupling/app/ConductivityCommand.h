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
  std::vector<double> pressures_Pa;  // empty: the bed as the scene gives it
  bool quiet = false;
  bool terminal = false;
};

int run_conductivity_command(const Scene& scene, const ConductivityCommandOptions& options,
                             std::ostream& out, std::ostream& log);

}  // namespace tmdem::coupling
