#pragma once
// Where a settle stands between two of its steps: what settle_packing (ThermalProblem.h) needs,
// beside the integrator's own state (MechanicsState.h), to go on bit for bit as if it had never
// stopped. An interrupted settle writes it into a settle checkpoint (RestartState.h), and a
// restart from that checkpoint resumes settling from it (docs/restart-and-files.md).
#include <cstdint>
#include <deque>

#include "coupling/run/SettleRestTest.h"

namespace tmdem::coupling {

struct SettleProgress {
  double time_s = 0.0;                 // settle time reached, s (steps x mechanics.time_step)
  std::int64_t steps = 0;              // this settle's steps so far
  std::int64_t unconverged_steps = 0;  // of them, those whose contact solve did not converge
  double max_penetration_m = 0.0;      // the largest penetration of any step so far
  bool finished = false;               // at rest, or mechanics.settle_time ran out
  std::deque<SettleRestTest::Snapshot> rest_window;  // the rest test's last steps (SettleRestTest.h)
};

}  // namespace tmdem::coupling
