#pragma once
// A contact-solver tolerance that is loose while the particles fall and tight once they have
// landed (scene keys mechanics.fall_tolerance, mechanics.fall_speed; NscdParameters).
//
// Why: when a poured fill lands (the "collapse" of bench_pour's 2,000 spheres, steps 49-122)
// every step brings new impacts, and a tight tolerance there costs max_iterations sweeps per
// step without converging; once the bed has landed, a loose tolerance leaves reactions that do
// not hold it (nncg at 1e-4: the bed creeps for the whole 5 s settle). docs/mechanics.md "A tolerance
// schedule".
//
// The rule, one-way for the particles so that it cannot chatter, judged on two speeds of the
// state a step starts from: v_share, the speed that NscdParameters::fall_share of the moving
// particles reach (at least one; NscdIntegrator::fall_judged_speed()), and v_max, the largest
// (NscdIntegrator::max_speed()), each a moving wall's speed if larger:
//   before:  v_share has not reached fall_speed yet   -> tolerance (tight)
//   falling: from v_share >= fall_speed until v_max < fall_speed
//                                                    -> fall_tolerance (or tolerance if looser)
//   landed:  v_max < fall_speed after falling          -> tolerance, for the rest of the run
//            (unless a piston compacts the bed again: below)
// A fall begins when a share of the particles falls, so that the few spheres that always roll
// down a laid bed's surface do not put the whole bed at fall_tolerance; it ends when the last
// one has landed, so that a pour is not switched to the tight tolerance while its tail still
// lands (that switch cost pour_3d 13% more time, three seeds; docs/mechanics.md).
// A scene whose particles never reach fall_speed is solved at `tolerance` throughout.
// With tighten_steps N > 1 the landed steps j = 1, 2, ... (j = 1: the first one) use
// fall_tolerance (tolerance / fall_tolerance)^(j / N) until j = N reaches `tolerance`: the
// first step at 1e-5 after 1e-4 took 577-2,000+ sweeps on the 2,000 pour (docs/mechanics.md "A tolerance
// schedule"), and a geometric ramp spreads that work over N steps. A landed bed given a new
// piston load ramps again from fall_tolerance (ramp_again_from): it compacts as after a landing.
// A piston compacting the bed (NscdIntegrator::piston_compacting: moving at or above its
// compaction speed) makes the phase falling from any phase, and the fall then ends only once no
// piston compacts either: a loaded bed that flows creeps at the edge of jamming, and solved at
// `tolerance` those steps stall just above it, thousands of sweeps each (a plate started on
// deep_steel's top, a piston pressing a poured bed; docs/mechanics.md "A tolerance schedule").
// A collapse (begin_collapse): a step that ends unconverged outside a fall while fall_share of
// the moving particles move at kCollapseSpeedFraction x fall_speed or faster (at the step's
// start, or at the end of its failed try: a laid bed gives way from rest) is taken again at
// fall_tolerance (NscdIntegratorRetry.cpp), and the phase is Collapsing until the
// fastest particle is below that slower speed; then Landed, and the ramp. Why: a bed laid by
// deposition that gives way under its own weight (bench/beds/deposit_2d_sizes: 2D disks of radii
// 0.3 to 1.2 mm) creeps at 3-30% of fall_speed through hundreds of steps, never a fall by the
// rule above, and at `tolerance` its steps stall one after another at 1.2-1.4e-4 (14 and 21
// unconverged steps on two seeds, the third not at rest in 600 s); with the collapse it comes
// to rest on the three seeds with no step unconverged (docs/mechanics.md "A tolerance
// schedule", "A bed that gives way is a collapse"). Only a failed step starts it: a bed whose
// every step converges keeps its bits.
#include <cstdint>

namespace tmdem::mechanics {

class ToleranceSchedule {
 public:
  enum class Phase : int { Before = 0, Falling = 1, Landed = 2, Collapsing = 3 };
  // The speed of a collapse, as a fraction of fall_speed (above).
  static constexpr double kCollapseSpeedFraction = 0.1;

  // What a restart needs (MechanicsState.h): the phase and the step that first used the tight
  // tolerance after the fall (0: none yet).
  struct State {
    Phase phase = Phase::Before;
    std::int64_t landed_step = 0;
  };

  ToleranceSchedule() = default;  // off: `tolerance` for every step
  // fall_tolerance 0: off. Throws std::invalid_argument for a negative or non-finite
  // fall_tolerance, tighten_steps < 1 or, when on, a fall_speed that is not > 0.
  ToleranceSchedule(double tolerance, double fall_tolerance, double fall_speed_m_per_s,
                    int tighten_steps = 1);

  bool enabled() const { return fall_tolerance_ > 0.0; }
  // A collapse would loosen the tolerance: a schedule whose fall_tolerance is no looser than
  // `tolerance` retakes nothing as a collapse (the retake would repeat the failed try).
  bool can_collapse() const { return enabled() && fall_tolerance_ > tolerance_; }
  double fall_speed_m_per_s() const { return fall_speed_m_per_s_; }
  // The tolerance while falling: fall_tolerance, or `tolerance` if that is looser.
  double fall_tolerance() const { return fall_tolerance_; }
  // The tolerance for step number `step` (1-based over the run), which starts from a state
  // whose share speed is `share_speed_m_per_s` and largest speed `max_speed_m_per_s`, with a
  // piston compacting the bed or not (above); advances the phase.
  double tolerance_for_step(double share_speed_m_per_s, double max_speed_m_per_s, std::int64_t step,
                            bool compacting = false);
  Phase phase() const { return state_.phase; }
  // Falling or collapsing: the steps solved at fall_tolerance.
  bool falling() const { return state_.phase == Phase::Falling || state_.phase == Phase::Collapsing; }
  double collapse_speed_m_per_s() const { return kCollapseSpeedFraction * fall_speed_m_per_s_; }
  // A step that ended unconverged from a state whose share speed (as tolerance_for_step's) is
  // `share_speed_m_per_s`: outside a fall, at or above collapse_speed_m_per_s(), the phase
  // becomes Collapsing and true is returned (the step is to be taken again); otherwise false.
  bool begin_collapse(double share_speed_m_per_s);
  // The first step after the fall (0: not landed yet); `tolerance` from landed_step() +
  // tighten_steps - 1 on.
  std::int64_t landed_step() const { return state_.landed_step; }

  // A landed bed given a new load (a piston's: NscdIntegrator::set_piston_load) compacts again
  // as after a landing: the ramp starts again from fall_tolerance at step `step` (1-based).
  // Nothing before the landing, nor with tighten_steps 1.
  void ramp_again_from(std::int64_t step) {
    if (state_.phase == Phase::Landed && tighten_steps_ > 1) state_.landed_step = step;
  }

  const State& state() const { return state_; }
  void restore(const State& state) { state_ = state; }

 private:
  double tolerance_ = 0.0;
  double fall_tolerance_ = 0.0;
  double fall_speed_m_per_s_ = 0.0;
  int tighten_steps_ = 1;
  State state_;
};

}  // namespace tmdem::mechanics
