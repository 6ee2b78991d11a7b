// The end-of-run warning line (coupling/app/RunEndReport.h): it names how many warnings were
// printed during the run, one per unconverged step of the time step, the first 10; where steps
// were taken in parts, unconverged_steps counts each unconverged part and the line says both.
#include <gtest/gtest.h>

#include <sstream>

#include "coupling/app/RunEndReport.h"

namespace tmdem::coupling {
namespace {

std::string run_end_of(std::int64_t unconverged_parts, std::int64_t unconverged_time_steps) {
  RunSummary summary;
  summary.mechanics.steps = 100;
  summary.mechanics.unconverged_steps = unconverged_parts;
  summary.mechanics.unconverged_time_steps = unconverged_time_steps;
  std::ostringstream out;
  print_run_end(summary, Scene{}, "", false, out);
  return out.str();
}

TEST(RunEndReport, WarningLineCountsWholeStepsWhenNoneWasTakenInParts) {
  EXPECT_NE(run_end_of(12, 12).find("warnings: 12 mechanics steps unconverged, the first 10 printed above:"),
            std::string::npos)
      << run_end_of(12, 12);
  EXPECT_NE(run_end_of(3, 3).find("warnings: 3 mechanics steps unconverged, all printed above:"),
            std::string::npos);
  EXPECT_EQ(run_end_of(0, 0).find("warnings:"), std::string::npos);
}

TEST(RunEndReport, WarningLineSaysHowManyStepsWereWarnedWhenPartsFailed) {
  // Three steps retaken in parts whose parts failed 12 times in all: 3 warnings were printed,
  // not 10.
  const std::string three = run_end_of(12, 3);
  EXPECT_NE(three.find("warnings: 12 mechanics steps unconverged, counting each part of a step "
                       "taken in parts; of 3 steps of the time step, all printed above:"),
            std::string::npos)
      << three;
  const std::string many = run_end_of(40, 15);
  EXPECT_NE(many.find("of 15 steps of the time step, the first 10 printed above:"), std::string::npos)
      << many;
}

}  // namespace
}  // namespace tmdem::coupling
