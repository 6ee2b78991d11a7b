#pragma once
// `tmdem check`: how far a particle can move in one mechanics step, v h, against the smallest
// radius r_min, and whether that matters.
//
// What does not depend on it: tunnelling. The candidate margin is never below twice the
// largest look-ahead 2 h (|v| + h |g|) (mechanics/detection/ContactDetector.h), so every pair that can
// meet within a step is listed, at any speed, and the linearised gap of a step (normal frozen
// at its start) is a lower bound of the true gap of two spheres or a sphere and a plane, so a
// step can stop a particle early, never let it through (tested at 1.5 radii per step).
//
// What does: stopping early. A pair whose relative displacement in a step has a sideways part
// d is held at a true gap of up to sqrt(S^2 + d^2) - S, S = R_i + R_j (a "ghost gap"), while
// its contact carries force; at most sqrt((2 r_min)^2 + (v h)^2) - 2 r_min, about
// (v h)^2 / (4 r_min) for a travel well below r_min and never more than the travel itself. How much that matters depends on what is handed over:
//  - "dynamic": every step's contacts go to the thermal side (H = 2 k a, a from the force), so
//    a contact held at a ghost gap conducts as if touching. Warn when the ghost gap can exceed
//    r_min / 16: v h > kDynamicTravelFraction r_min = r_min / 2.
//  - "settle": only the packing at rest is handed over; there speeds are below
//    settle_velocity and ghost gaps vanish, so the travel of the fall changes the path the
//    particles took, as the seed does. Measured on the default scene (docs/mechanics.md "Travel per
//    step"): 1.40 r_min per step gives the same bed height and hot-particle temperatures as
//    0.36 r_min, within the seed-to-seed scatter. Warn beyond one smallest diameter per step,
//    v h > kSettleTravelFraction r_min = 2 r_min: the ghost gap can then exceed r_min, so a
//    particle can be stopped by a neighbour it would not have reached within the step.
//
// The speed is estimated from gravity and pistons (scenes have no initial velocities): an
// upper bound of the largest speed of the run where things fall freely, not of what a load
// makes a bed do (a laid bed that collapses under a plate):
//   particles: v = |g| t, t = mechanics.settle_time ("settle") or simulation.duration
//   ("dynamic"), capped by free fall onto the floor, v = sqrt(2 |g| H), when the scene has one
//   (a plane wall facing against gravity, n . g < 0, or a cylinder wall whose axis is not along
//   gravity): H is the largest fall of a particle along gravity until it meets the nearest
//   floor below it. A particle resting at the start on something below it that rests too (a
//   wall facing up, a fixed particle, a resting particle lower along gravity: a bed laid by
//   deposition or imported) does not fall, so a laid bed without a piston gets no speed;
//   pistons (and the particles they push): v = a t with a = force / mass + g . n, capped by
//   sqrt(2 a D), D the distance along n to the nearest plane wall it moves towards.
#include <cmath>
#include <cstddef>
#include <vector>

#include "coupling/scene/Scene.h"
#include "mechanics/detection/TouchingPairs.h"

namespace tmdem::coupling {

inline constexpr double kDynamicTravelFraction = 0.5;  // of r_min per step, "dynamic" runs
inline constexpr double kSettleTravelFraction = 2.0;   // of r_min per step, "settle" runs

struct StepTravel {
  double speed_m_per_s = 0.0;      // estimated largest speed
  double travel_m = 0.0;           // speed x mechanics.time_step
  double smallest_radius_m = 0.0;  // of a moving particle
  double fraction = kSettleTravelFraction;  // of smallest_radius_m: the limit of this mode
  std::size_t resting_particles = 0;  // moving particles resting at the start on what rests (no fall)
  double limit_m() const { return fraction * smallest_radius_m; }
  bool too_far() const { return travel_m > limit_m(); }
  // The largest ghost gap, m. Exact, not the small-travel (v h)^2 / (4 r_min): that grows past
  // the travel itself (a 0.09 m step against 0.8 mm spheres: 2.4 m apart, in a 2 cm box).
  double ghost_gap_m() const {
    // sqrt(s^2 + d^2) - s without the cancellation of a travel far below the radius.
    const double s = 2.0 * smallest_radius_m;
    return travel_m * travel_m / (std::sqrt(s * s + travel_m * travel_m) + s);
  }
};

// Touching at the start: within this fraction of the radius (the loader's wall tolerance).
inline constexpr double kRestingOverlapFraction = 1e-9;

// Zero travel when mechanics is off or nothing moves. `touching`: the pairs touching at the
// start (mechanics::find_touching_pairs of the scene's particles and walls, within
// kRestingOverlapFraction), for a caller that has them; the first form finds them itself.
StepTravel estimate_step_travel(const Scene& scene);
StepTravel estimate_step_travel(const Scene& scene, const std::vector<mechanics::TouchingPair>& touching);

}  // namespace tmdem::coupling
