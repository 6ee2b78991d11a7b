#pragma once
// The final lines of `tmdem run` on stderr, in this order: where the result went; where the
// wall time went (timing table); a count per kind of warning with one line of advice each (the
// run prints at most 10 warnings of a kind, the counts are the true ones, from the summary); the
// mechanics figures (largest penetration, unconverged and stalled steps); and, for a settle run
// whose packing was frozen before it came to rest, a warning that says so (also with --quiet:
// it qualifies every result).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "coupling/output/RunSummary.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// wrote_path: the result file (the "wrote" line only when not empty); quiet drops everything
// but the not-at-rest warning.
void print_run_end(const RunSummary& summary, const Scene& scene, const std::string& wrote_path,
                   bool quiet, std::ostream& out);

// One row of the timing table.
struct TimingRow {
  std::string part;      // "contact detection", "contact solve", "penetration correction",
                         // "thermal", "output", "other"
  double seconds = 0.0;
  double share = 0.0;    // of the rows' total (= wall_time_s); the shares add up to 1
};
// The rows of summary.wall_time_parts, in that order; empty without it. "other" is other_s plus
// the part of mechanics_s outside detection, solve and correction (the step's bookkeeping), so
// the rows add up to wall_time_s.
std::vector<TimingRow> timing_rows(const RunSummary& summary);

// One kind of warning the run can repeat, with its true count.
struct WarningCount {
  std::string kind;       // "contact solve not converged", ...
  std::int64_t count = 0;
  std::string advice;     // one line
};
// The kinds with a count above 0: contact solves that did not converge (not stalled) and
// contact solves that stalled (summary.mechanics). A packing frozen before it came to rest has
// its own last line.
std::vector<WarningCount> warning_counts(const RunSummary& summary);

// Warnings of one kind printed during a run: the first 10.
inline constexpr std::int64_t kWarningsShown = 10;

}  // namespace tmdem::coupling
