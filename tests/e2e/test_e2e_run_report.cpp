// End to end: the final lines of a dynamic run. The timing table has its six rows (detection,
// contact solve and penetration correction timed inside the steps), their shares add up to 1 and their seconds to the run's wall time (summary "wall_time_parts"); the
// warnings summary gives the true count per kind, which the summary's counters also give,
// while only the first 10 warnings are printed.
#include <gtest/gtest.h>

#include <sstream>

#include "E2eSupport.h"
#include "coupling/app/RunEndReport.h"
#include "coupling/output/RunSummary.h"

using namespace tmdem::e2e;

namespace {

TEST(EndToEndRunReport, TimingTableAndWarningCountsMatchTheSummary) {
  const auto dir = scratch_dir("run_report");
  // The poured bed with nncg cut to 100 sweeps: many of its 400 steps do not converge (48 above
  // the tolerance in Siconos' measure; nncg_ipm, the default, converges all but 2 of them), not
  // retaken in parts, so that each counts once.
  const auto r = run_tmdem("run " + std::string(TMDEM_SOURCE_DIR) +
                               "/examples/poured_bed.toml -o bed.h5 --summary s.json "
                               "--set simulation.duration=0.4 --set mechanics.max_iterations=100 --set mechanics.solver=\\\"nncg\\\" "
                               "--set mechanics.retry_parts=1",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = read_summary(dir + "/s.json");
  ASSERT_TRUE(json.contains("wall_time_parts")) << json.dump(2);
  const auto summary = tmdem::coupling::RunSummary::from_json(json);

  // Timing: six rows, shares summing to 1, seconds to the wall time; each row printed.
  const auto rows = tmdem::coupling::timing_rows(summary);
  ASSERT_EQ(rows.size(), 6u);
  double share = 0.0, seconds = 0.0;
  for (const auto& row : rows) {
    share += row.share;
    seconds += row.seconds;
    EXPECT_GE(row.seconds, 0.0);
    EXPECT_NE(r.output.find("  " + row.part), std::string::npos) << row.part << "\n" << r.output;
  }
  EXPECT_NEAR(share, 1.0, 1e-12);
  EXPECT_NEAR(seconds, summary.wall_time_s, 1e-9 * summary.wall_time_s);
  const auto& parts = *summary.wall_time_parts;
  EXPECT_GT(rows[0].seconds, 0.0);  // detection and solve in each of 400 steps
  EXPECT_GT(rows[1].seconds, 0.0);
  EXPECT_GT(rows[4].seconds, 0.0);  // 9 frames were written
  EXPECT_EQ(rows[0].seconds, parts.detection_s);
  EXPECT_EQ(rows[1].seconds, parts.contact_solve_s);
  EXPECT_EQ(rows[2].seconds, parts.correction_s);
  EXPECT_GE(parts.correction_s, 0.0);
  // The three are timed inside the steps that mechanics_s times from outside.
  EXPECT_LE(parts.detection_s + parts.contact_solve_s + parts.correction_s, parts.mechanics_s);
  // "other" holds other_s and the rest of the steps, nothing else.
  EXPECT_NEAR(rows[5].seconds,
              parts.other_s + parts.mechanics_s - parts.detection_s - parts.contact_solve_s -
                  parts.correction_s,
              1e-12 * summary.wall_time_s);
  EXPECT_EQ(summary.wall_time_parts->thermal_s, summary.thermal.wall_time_s);
  EXPECT_NE(r.output.find("timing (wall time "), std::string::npos) << r.output;

  // Warnings: the true count per kind, as the summary counts them; 10 printed during the run.
  const auto& m = summary.mechanics;
  ASSERT_GT(m.unconverged_steps, 10) << r.output;
  EXPECT_EQ(count_of(r.output, "warning: mechanics step at t = "), 10u) << r.output;
  EXPECT_NE(r.output.find("further such warnings are not shown"), std::string::npos);
  EXPECT_NE(r.output.find("warnings: " + std::to_string(m.unconverged_steps) +
                          " mechanics steps unconverged, the first 10 printed above:"),
            std::string::npos) << r.output;
  const auto kinds = tmdem::coupling::warning_counts(summary);
  std::int64_t total = 0;
  for (const auto& kind : kinds) {
    total += kind.count;
    EXPECT_NE(r.output.find("  " + std::to_string(kind.count) + " x " + kind.kind + ": "),
              std::string::npos) << kind.kind << "\n" << r.output;
  }
  EXPECT_EQ(total, m.unconverged_steps);
  EXPECT_EQ(kinds.front().count, m.unconverged_steps - m.stalled_steps);
}

// The default solver's fallback in the summary and the end-of-run line: the same poured bed with
// nncg_ipm cut to 100 sweeps of nncg, not retaken, so that each step is one solve. Every solve
// nncg leaves above the tolerance is handed on; those the later stages do not converge are the
// run's unconverged steps. A solver without later stages writes no block.
TEST(EndToEndRunReport, TheFallbacksWorkIsInTheSummaryAndTheLastLines) {
  const auto dir = scratch_dir("run_report_fallback");
  const std::string common = "run " + std::string(TMDEM_SOURCE_DIR) +
                             "/examples/poured_bed.toml -o bed.h5 --overwrite --set simulation.duration=0.2 "
                             "--set mechanics.max_iterations=100 --set mechanics.retry_parts=1 ";
  const auto r = run_tmdem(common + "--summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto json = read_summary(dir + "/s.json");
  ASSERT_TRUE(json["mechanics"].contains("fallback")) << json.dump(2);
  const auto summary = tmdem::coupling::RunSummary::from_json(json);
  const auto& m = summary.mechanics;
  const auto& f = *m.fallback;
  const std::int64_t converged = f.converged_by_second + f.converged_by_first_again + f.converged_by_sweeps;
  ASSERT_GT(f.solves, 10) << r.output;  // the test acts: nncg at 100 sweeps leaves many
  EXPECT_GT(converged, 0);
  // Handed on within the tolerance already (Siconos' measure, which judges the steps): converged
  // steps, not by the stages.
  EXPECT_EQ(f.solves - converged - f.within_when_handed_on, m.unconverged_steps) << r.output;
  EXPECT_GT(f.sweeps, 0);
  EXPECT_GT(f.seconds, 0.0);
  EXPECT_LE(f.seconds, summary.wall_time_parts->contact_solve_s);
  // nncg ran out of its 100 sweeps on each solve it handed on (or stalled before).
  EXPECT_GT(f.first_sweeps, 0);
  EXPECT_LE(f.first_sweeps, 100 * f.solves);
  EXPECT_GT(f.first_seconds, 0.0);
  EXPECT_LE(f.seconds + f.first_seconds, summary.wall_time_parts->contact_solve_s);
  EXPECT_NE(r.output.find("mechanics: " + std::to_string(f.solves) + " solves handed on by the first solver, " +
                          std::to_string(converged) + " then converged"),
            std::string::npos) << r.output;

  const auto plain = run_tmdem(common + "--summary p.json --set mechanics.solver=\\\"nncg\\\"", dir);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_FALSE(read_summary(dir + "/p.json")["mechanics"].contains("fallback"));
  EXPECT_EQ(plain.output.find("solves handed on"), std::string::npos);
}

}  // namespace
