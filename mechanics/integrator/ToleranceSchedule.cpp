#include "mechanics/integrator/ToleranceSchedule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tmdem::mechanics {

ToleranceSchedule::ToleranceSchedule(double tolerance, double fall_tolerance,
                                     double fall_speed_m_per_s, int tighten_steps)
    : tolerance_(tolerance),
      fall_tolerance_(fall_tolerance),
      fall_speed_m_per_s_(fall_speed_m_per_s),
      tighten_steps_(tighten_steps) {
  if (tighten_steps < 1) throw std::invalid_argument("mechanics: tighten_steps must be >= 1");
  if (!(fall_tolerance >= 0.0 && std::isfinite(fall_tolerance)))
    throw std::invalid_argument("mechanics: fall_tolerance must be >= 0 (0: no tolerance schedule)");
  if (enabled() && !(fall_speed_m_per_s > 0.0 && std::isfinite(fall_speed_m_per_s)))
    throw std::invalid_argument("mechanics: fall_speed must be > 0 (m/s) with a fall_tolerance");
  // A fall tolerance tighter than `tolerance` would make the fall the hardest part of the run.
  if (enabled()) fall_tolerance_ = std::max(fall_tolerance_, tolerance_);
}

double ToleranceSchedule::tolerance_for_step(double share_speed_m_per_s, double max_speed_m_per_s,
                                             std::int64_t step, bool compacting) {
  if (!enabled()) return tolerance_;
  // A load compacting the bed, from any phase (a landed bed too: the load makes it flow again).
  if (compacting) state_.phase = Phase::Falling;
  switch (state_.phase) {
    case Phase::Before:
      if (share_speed_m_per_s >= fall_speed_m_per_s_) state_.phase = Phase::Falling;
      break;
    case Phase::Falling:
      if (max_speed_m_per_s < fall_speed_m_per_s_ && !compacting) {
        state_.phase = Phase::Landed;
        state_.landed_step = step;
      }
      break;
    case Phase::Collapsing:
      if (max_speed_m_per_s < collapse_speed_m_per_s() && !compacting) {
        state_.phase = Phase::Landed;
        state_.landed_step = step;
      }
      break;
    case Phase::Landed:
      break;
  }
  if (falling()) return fall_tolerance_;
  const std::int64_t j = state_.phase == Phase::Landed ? step - state_.landed_step + 1 : tighten_steps_;
  if (j >= tighten_steps_) return tolerance_;
  return fall_tolerance_ * std::pow(tolerance_ / fall_tolerance_, double(j) / double(tighten_steps_));
}

bool ToleranceSchedule::begin_collapse(double share_speed_m_per_s) {
  if (!can_collapse() || falling()) return false;
  if (!(share_speed_m_per_s >= collapse_speed_m_per_s())) return false;
  state_.phase = Phase::Collapsing;
  return true;
}

}  // namespace tmdem::mechanics
