#pragma once
// `tmdem check`: how far a particle can move in one mechanics step, v h, against the smallest
// radius. Contacts are still found (the candidate margin grows with the look-ahead v h, so
// nothing tunnels; tested at 1.5 radii per step), but a step's contact normals and gaps are
// those of its start. Two spheres passing each other by d sideways within a step keep a true
// gap larger than the linearised one by up to d^2 / (2 (R_i + R_j)), so a contact can act that
// much too early: with d = r_min / 2, r_min / 16 at most. Beyond, oblique impacts get coarse and
// the look-ahead makes candidate tables large.
//
// The speed is estimated from gravity alone (scenes have no initial velocities):
//   v = |g| t, t = mechanics.settle_time ("settle") or simulation.duration ("dynamic"),
// capped by free fall onto the floor, v = sqrt(2 |g| H), when the scene has one (a plane wall
// facing against gravity, n . g < 0): H is the largest height of a particle centre above the
// nearest floor below it, measured along gravity. A warning when v h > kStepTravelFraction of
// the smallest radius.
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

inline constexpr double kStepTravelFraction = 0.5;

struct StepTravel {
  double speed_m_per_s = 0.0;      // estimated largest speed
  double travel_m = 0.0;           // speed x mechanics.time_step
  double smallest_radius_m = 0.0;  // of a moving particle
  bool too_far() const { return travel_m > kStepTravelFraction * smallest_radius_m; }
};

// Zero travel when mechanics is off or nothing moves.
StepTravel estimate_step_travel(const Scene& scene);

}  // namespace tmdem::coupling
