#pragma once
// The final lines of `tmdem run` on stderr: where the result went, the mechanics figures (largest
// penetration, unconverged and stalled steps) and, for a settle run whose packing was frozen
// before it came to rest, a warning that says so (also with --quiet: it qualifies every result).
#include <ostream>
#include <string>

#include "coupling/output/RunSummary.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// wrote_path: the result file (the "wrote" line only when not empty); quiet drops everything
// but the not-at-rest warning.
void print_run_end(const RunSummary& summary, const Scene& scene, const std::string& wrote_path,
                   bool quiet, std::ostream& out);

}  // namespace tmdem::coupling
