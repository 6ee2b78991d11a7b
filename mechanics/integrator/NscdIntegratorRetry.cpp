// NscdIntegrator::step(double): a step that ends unconverged taken again from its start in
// shorter equal parts (NscdParameters::retry_parts; docs/mechanics.md "Retaking an unconverged
// step"), apart from the step itself (NscdIntegrator.cpp), as the state's save and restore are.
#include <algorithm>
#include <cmath>

#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/model/StepInterrupt.h"

namespace tmdem::mechanics {

StepReport NscdIntegrator::step(double h) {
  StepReport report = step_with_retries(h);
  if (!report.converged && !report.interrupted) ++stats_.unconverged_time_steps;
  if (step_observer_ && !report.interrupted) step_observer_(h, report);
  return report;
}

StepReport NscdIntegrator::step_with_retries(double h) {
  // The start of the step, to take it again in parts if it ends unconverged, or to put it back
  // if it is given up (StepInterrupt.h). restore_state takes the state as a checkpoint's,
  // whose warm start is its own: the first step's pending static warm start and held overlaps
  // are put back by hand.
  save_state(retry_start_);
  const bool static_start_pending = static_start_pending_;
  retry_holds_overlap_ = holds_overlap_;
  const auto back_to_start = [&] {
    restore_state(retry_start_);
    static_start_pending_ = static_start_pending;
    holds_overlap_ = retry_holds_overlap_;
  };
  std::int64_t discarded_sweeps = 0;
  double discarded_detection_s = 0.0, discarded_solve_s = 0.0, discarded_correction_s = 0.0;
  FallbackCounts discarded_fallback;  // the solver's later stages in the tries thrown away
  // Given up: the state and counters of the start, but the time spent stays in the timing.
  const auto given_up = [&](const StepReport& last_try) {
    back_to_start();
    stats_.detection_s += discarded_detection_s + last_try.detection_s;
    stats_.solve_s += discarded_solve_s + last_try.solve_s;
    stats_.correction_s += discarded_correction_s + last_try.correction_s;
    stats_.fallback += discarded_fallback;
    stats_.fallback += last_try.fallback;
    StepReport none;
    none.converged = false;
    none.interrupted = true;
    return none;
  };
  // The speed a collapse is judged on (ToleranceSchedule::begin_collapse): fall_share's speed at
  // the start, or at the end of the failed try (a laid bed that gives way in its first step
  // starts at rest); only outside a fall (O(n), no allocation).
  // (Not with equal tolerances: thermal_cycling at tolerance = fall_tolerance = 1e-4 retook 4
  // steps as collapses that repeated their failed tries bit for bit.)
  const bool may_collapse = schedule_.can_collapse() && !schedule_.falling() && parameters_.retry_parts >= 2;
  double share_speed_m_per_s = may_collapse ? fall_judged_speed() : 0.0;
  bool collapsing = false;
  const auto take_again_from_start = [&] {
    back_to_start();
    // restore_state put the schedule back too: a collapse begun by this step stands for its
    // retries.
    if (collapsing) schedule_.begin_collapse(share_speed_m_per_s);
  };
  // A try thrown away: its sweeps and times kept apart.
  const auto discard = [&](const StepReport& thrown) {
    discarded_sweeps += thrown.sweeps;
    discarded_detection_s += thrown.detection_s;
    discarded_solve_s += thrown.solve_s;
    discarded_correction_s += thrown.correction_s;
    discarded_fallback += thrown.fallback;
  };
  // The parts this step starts in: those the last retry needed, while they are kept
  // (NscdParameters::retry_keep_steps), within the retry's budget.
  const int limit = retry_limit_ > 0 ? retry_limit_ : parameters_.retry_parts;
  const bool keeps_parts = parameters_.retry_parts >= 2 && parameters_.retry_keep_steps > 0;
  const int start = keeps_parts ? std::clamp(start_parts_, 1, limit) : 1;
  const auto first_try = [&] {
    return start > 1 ? step_in_parts(h / double(start), start, true) : step(h, true);
  };
  // The solver's later stages (NscdParameters::fallback_on_last_try) only on a try that no
  // retry would follow; `last`: whether the try about to be taken is known to be such a one.
  // (A first try that may be retaken as a collapse is not known to be: that depends on how it
  // ends.) The guard hands on again whatever way the step ends.
  const bool withhold = parameters_.fallback_on_last_try && parameters_.retry_parts >= 2 && solver_->has_fallback();
  const auto hand_on_if = [&](bool last) { set_hand_on(!withhold || last); };
  struct HandOnAgain {
    NscdIntegrator& integrator;
    ~HandOnAgain() { integrator.set_hand_on(true); }
  } hand_on_again{*this};
  hand_on_if(2 * start > limit && !may_collapse);
  StepReport report = first_try();
  if (step_interrupt_requested()) return given_up(report);
  if (parameters_.retry_parts < 2) return report;
  if (!report.converged && may_collapse) share_speed_m_per_s = std::max(share_speed_m_per_s, fall_judged_speed());
  // A bed that creeps outside a fall and stalls at `tolerance`: the step taken again as first
  // taken (whole, or in its kept parts), at fall_tolerance, the bed now collapsing
  // (ToleranceSchedule.h).
  // (Not a step the schedule solved as a fall, at fall_tolerance already: one that began a fall.)
  if (!report.converged && may_collapse && !report.fall &&
      share_speed_m_per_s >= schedule_.collapse_speed_m_per_s()) {
    collapsing = true;
    discard(report);
    take_again_from_start();
    hand_on_if(2 * start > limit);
    report = first_try();
    if (step_interrupt_requested()) return given_up(report);
  }
  // Parts relative to the first try's own: a landing already taken in parts of h / 8
  // (periodic_2d's piston) retaken in 2 parts of h / 2 repeats, part for part, the very same
  // steps; so the retries go to parts of h / 16, h / 32 and h / 64 there.
  // The kept parts count towards the limit; a landing's own do not.
  const int landing_parts = int(std::max(1L, std::lround(h / report.time_step_s / double(start))));
  int finer = start, parts = start;
  while (!report.converged && 2 * finer <= limit) {
    finer *= 2;
    parts = landing_parts * finer;
    discard(report);
    take_again_from_start();
    hand_on_if(2 * finer > limit);
    report = step_in_parts(h / double(parts), parts, true);
    if (step_interrupt_requested()) return given_up(report);
  }
  // The last try, unconverged, was taken without the later stages: once more with them, as it
  // was taken (a first try that was not retaken as a collapse, where the budget allows no parts).
  bool again_handed_on = false;
  if (!report.converged && !hand_on_) {
    again_handed_on = true;
    discard(report);
    take_again_from_start();
    hand_on_if(true);
    report = finer > start ? step_in_parts(h / double(parts), parts, true) : first_try();
    if (step_interrupt_requested()) return given_up(report);
  }
  if (finer > start || collapsing || again_handed_on) {
    // restore_state put back the counters of the start: the retry's own go on top of the
    // parts' (each part counted as a step), and the discarded tries' time with the rest.
    report.retry_parts = parts;
    report.collapse = collapsing;
    report.discarded_sweeps = discarded_sweeps;
    report.detection_s += discarded_detection_s;
    report.solve_s += discarded_solve_s;
    report.correction_s += discarded_correction_s;
    ++stats_.retried_steps;
    if (collapsing) ++stats_.collapse_steps;
    stats_.discarded_sweeps += discarded_sweeps;
    stats_.detection_s += discarded_detection_s;
    stats_.solve_s += discarded_solve_s;
    stats_.correction_s += discarded_correction_s;
    stats_.fallback += discarded_fallback;
  }
  // The budget (after the restores above, which put back the start's). Why: where a bed's steps
  // stall one after another (bench/beds/deposit_2d_sizes: 30 of 56 steps, laid and loaded),
  // retaking each in up to 8 parts costs 15 of its tries and changes nothing; a retry that
  // failed says so, and the next ones are cut.
  if (!report.converged) {
    retry_limit_ = std::max(1, limit / 2);
    retry_converged_in_a_row_ = 0;
  } else if (++retry_converged_in_a_row_ >= kRetryRecoverSteps) {
    retry_limit_ = std::min(parameters_.retry_parts, 2 * limit);
    retry_converged_in_a_row_ = 0;
  }
  // The parts kept for the next steps: a bed's hard spell (thermal_cycling's re-settles, a
  // piston compacting) outlasts the step, and its whole tries stall before their parts converge.
  // A step that converged in parts raises them; retry_keep_steps converged in a row halve them.
  // A step still unconverged keeps them (its parts did not help, its whole step would not either).
  if (start > 1) {
    report.start_parts = start;
    ++stats_.kept_parts_steps;
  }
  if (keeps_parts) {
    // (start, not start_parts_, where they stay: kept parts the budget cut are dropped, not put
    // back when the budget recovers many steps on.)
    if (!report.converged) {
      start_parts_ = start;
      start_parts_converged_in_a_row_ = 0;
    } else if (finer > start) {
      start_parts_ = finer;
      start_parts_converged_in_a_row_ = 0;
    } else if (start > 1 && ++start_parts_converged_in_a_row_ >= parameters_.retry_keep_steps) {
      start_parts_ = start / 2;
      start_parts_converged_in_a_row_ = 0;
    } else {
      start_parts_ = start;
    }
  }
  return report;
}

}  // namespace tmdem::mechanics
