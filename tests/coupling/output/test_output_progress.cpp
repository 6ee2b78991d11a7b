// The progress line's time-left estimate: the rest of the phase at its mean rate so far.
#include <gtest/gtest.h>

#include <sstream>

#include "coupling/output/ProgressReporter.h"

namespace tmdem::coupling {
namespace {

TEST(ProgressEta, ExtrapolatesThePhasesMeanRate) {
  // 10 s of 100 s simulated in 5 s of wall time: 90 s left at 0.5 wall s per s.
  EXPECT_EQ(eta_text(0.0, 10.0, 100.0, 5.0), "ETA 45 s");
  // A phase that began at t = 50 s (a restart): only its own progress counts.
  EXPECT_EQ(eta_text(50.0, 60.0, 100.0, 5.0), "ETA 20 s");
  EXPECT_EQ(eta_text(0.0, 1.0, 100.0, 60.0), "ETA 99.0 min");   // 5,940 s
  EXPECT_EQ(eta_text(0.0, 1.0, 1001.0, 60.0), "ETA 16.7 h");    // 60,000 s
  EXPECT_EQ(eta_text(0.0, 100.0, 100.0, 5.0), "ETA 0 s");
}

TEST(ProgressEta, SaysNothingWithoutProgressToExtrapolate) {
  EXPECT_EQ(eta_text(0.0, 0.0, 100.0, 5.0), "");    // no simulated time yet
  EXPECT_EQ(eta_text(0.0, 10.0, 100.0, 0.05), "");  // under 0.1 s of wall time
}

TEST(ProgressEta, FirstLineOfAPhaseHasNoEstimate) {
  std::ostringstream out;
  ProgressReporter progress(out, false, false);
  progress.update("run", 1.0, 10.0);
  EXPECT_EQ(out.str().find("ETA"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("run: t = 1 / 10 s (10.0%)"), std::string::npos) << out.str();
}

}  // namespace
}  // namespace tmdem::coupling
