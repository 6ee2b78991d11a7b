// RestartState: the mechanics' state through the checkpoint's flat form and back. The detector's
// mark of a table a landing piston widened (ContactDetector::widened_by_wall) decides whether the
// next step rebuilds it, so a restart that lost it would leave the widened table in place where
// the uninterrupted run rebuilt it.
#include <gtest/gtest.h>

#include "coupling/run/RestartState.h"

namespace tmdem::coupling {
namespace {

mechanics::MechanicsState two_spheres(bool widened) {
  mechanics::MechanicsState s;
  s.position_m = {{0.0, 0.0, 0.0}, {0.0, 2e-3, 0.0}};
  s.velocity_m_per_s = {{0.0, 0.0, 0.0}, {0.0, -0.1, 0.0}};
  s.angular_velocity_rad_per_s = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  s.margin_m = 8e-3;
  s.wall_margin_m = 8e-3;
  s.margin_widened_by_wall = widened;
  s.rebuilds = 3;
  s.reference_position_m = s.position_m;
  s.candidates = {{0, 1}};
  s.candidate_force_N = {{1e-3, 0.0, 0.0}};
  return s;
}

TEST(RestartState, TheMarkOfATableALandingWidenedGoesThroughTheCheckpoint) {
  for (const bool widened : {true, false}) {
    CheckpointState cs;
    store_mechanics_state(two_spheres(widened), cs);
    const mechanics::MechanicsState back = mechanics_state_of(cs);
    EXPECT_EQ(back.margin_widened_by_wall, widened);
    EXPECT_EQ(back.margin_m, 8e-3);
    EXPECT_EQ(back.wall_margin_m, 8e-3);
  }
  // A checkpoint written before the mark existed: not widened (the table kept as it was).
  CheckpointState older;
  store_mechanics_state(two_spheres(true), older);
  older.extra.erase("mechanics_margin_widened_by_wall");
  EXPECT_FALSE(mechanics_state_of(older).margin_widened_by_wall);
}

// The run's count of the default solver's later stages goes through the checkpoint, so a
// restarted run's summary counts the whole run; their seconds, like the other times, count from
// the restart (MechanicsStats).
TEST(RestartState, TheFallbackCountsGoThroughTheCheckpoint) {
  mechanics::MechanicsStats stats;
  stats.fallback = mechanics::FallbackCounts{17, 9, 4, 2, 1, 123456, 3.5, 170000, 8.5};
  CheckpointState cs;
  store_mechanics_stats(stats, cs);
  const mechanics::MechanicsStats back = mechanics_stats_of(cs);
  EXPECT_EQ(back.fallback.solves, 17);
  EXPECT_EQ(back.fallback.converged_by_second, 9);
  EXPECT_EQ(back.fallback.converged_by_first_again, 4);
  EXPECT_EQ(back.fallback.converged_by_sweeps, 2);
  EXPECT_EQ(back.fallback.within_when_handed_on, 1);
  EXPECT_EQ(back.fallback.sweeps, 123456);
  EXPECT_EQ(back.fallback.seconds, 0.0);
  EXPECT_EQ(back.fallback.first_sweeps, 170000);
  EXPECT_EQ(back.fallback.first_seconds, 0.0);
  // A checkpoint written before the counts existed reads as none.
  EXPECT_EQ(mechanics_stats_of(CheckpointState{}).fallback.solves, 0);
}

}  // namespace
}  // namespace tmdem::coupling
