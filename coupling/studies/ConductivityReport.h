#pragma once
// The conductivity study's printed report and its CSV (columns in docs/conductivity-study.md).
#include <ostream>
#include <vector>

#include "coupling/studies/ConductivityStudy.h"

namespace tmdem::coupling {

void print_conductivity_report(std::ostream& out, const ConductivityResult& result);

// Header, then one row per result (one per load). The share_<mode> columns list every
// registered heat-transfer mode in registry order (0 for a mode that is off), so the columns
// depend only on the program version, not on the scene.
void write_conductivity_csv(std::ostream& out, const std::vector<ConductivityResult>& results);

}  // namespace tmdem::coupling
