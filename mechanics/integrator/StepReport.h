#pragma once
// What one mechanics step did, and the totals over a run (summary "mechanics" block).

#include <cstddef>
#include <cstdint>

namespace tmdem::mechanics {

// The contact solver's later stages (SolveReport::fallback_stage; FallbackContactSolver.h): the
// solves its first solver left unconverged and handed on, and of them those the step then counted
// as converged, by the stage that ended them; the iterations and wall time of those stages.
struct FallbackCounts {
  std::int64_t solves = 0;
  std::int64_t converged_by_second = 0;      // the second solver ("ipm")
  std::int64_t converged_by_first_again = 0; // the first solver once more, from the better result
  std::int64_t converged_by_sweeps = 0;      // plain sweeps (the polish)
  // Handed on within the tolerance by Siconos' measure already (the first's own stop test
  // unmet), whichever stage ended them: not in the three above, which the stages converged.
  std::int64_t within_when_handed_on = 0;
  std::int64_t sweeps = 0;                   // iterations of the later stages (in the steps' sweeps)
  double seconds = 0.0;                      // wall time of the later stages (in solve_s), s
  // The first solver's iterations and wall time, s, on the solves it handed on (in the steps'
  // sweeps and solve_s): what it spent before handing them on.
  std::int64_t first_sweeps = 0;
  double first_seconds = 0.0;
  FallbackCounts& operator+=(const FallbackCounts& other) {
    solves += other.solves;
    converged_by_second += other.converged_by_second;
    converged_by_first_again += other.converged_by_first_again;
    converged_by_sweeps += other.converged_by_sweeps;
    within_when_handed_on += other.within_when_handed_on;
    sweeps += other.sweeps;
    seconds += other.seconds;
    first_sweeps += other.first_sweeps;
    first_seconds += other.first_seconds;
    return *this;
  }
};

struct StepReport {
  // s: the length of the step problem() was built for (NscdIntegrator::problem()): h, or the
  // last part of a step taken in halves (`merged` keeps the second half's).
  double time_step_s = 0.0;
  int sweeps = 0;                  // Gauss-Seidel sweeps used
  double residual = 0.0;           // sum |dr| / sum |r| of the last sweep (see NscdParameters)
  bool converged = true;           // residual <= tolerance within max_iterations
  double tolerance = 0.0;          // the tolerance in force for this step (ToleranceSchedule.h)
  // Siconos' residual of the step's reactions relative to ||q|| (SiconosResidual.h), whatever
  // the solver's own stop test: the figure another code would report for the step.
  double siconos_residual = 0.0;
  // The natural-map residual in the bodies' metric (NaturalMapResidual.h: each reaction against
  // its own exact local solution, relative to the reactions). It sees what siconos_residual
  // does not: with rho = 1 an impulse defect counts in N s beside velocities in m/s, so on
  // light bodies a reaction outside its cone barely moves that figure (docs/mechanics.md
  // "Honest convergence"); it misses what that one sees, a slowly contracting solve.
  double natural_map_residual = 0.0;
  bool fall = false;               // solved at mechanics.fall_tolerance (the particles falling)
  bool stalled = false;            // the solver gave up early: no progress (not converged)
  int correction_sweeps = 0;       // penetration correction (PenetrationCorrection.h); 0: none
                                   // needed. Its failure makes the step unconverged too.
  // Potential-energy change of the penetration correction's displacements dx_i (moving
  // particles), -sum m_i g . dx_i, and a piston's -F . dx (load plus weight), J: > 0 when it
  // lifts particles. Outside the energy account below (that one covers the velocity step), so
  // the correction's work is seen on its own.
  double correction_potential_J = 0.0;
  double max_penetration_m = 0.0;  // largest overlap after the step, >= 0
  double max_travel_m = 0.0;       // largest particle displacement of the position update
                                   // h (theta v+ + (1 - theta) v-), m (correction excluded)
  std::size_t candidates = 0;      // contacts handed to the solver
  std::size_t active_contacts = 0; // contacts with r_n > 0
  bool rebuilt_candidates = false; // the candidate table was rebuilt this step
  // The step's table, listed with a piston's likely reach (NscdParameters::estimate_wall_reach),
  // did not hold the travel its solve gave: listed again with the bound and solved again (both
  // solves' sweeps in `sweeps`).
  bool relisted = false;
  // Energy account of the step (NscdIntegrator.h): energy_change + contact_dissipation +
  // numerical_dissipation = 0 up to round-off, all in J.
  double energy_change_J = 0.0;        // kinetic + gravitational potential, after - before
  double contact_dissipation_J = 0.0;  // -sum_c r_c . u_theta,c
  double numerical_dissipation_J = 0.0;  // (theta - 1/2) |v+ - v-|_M^2, 0 for theta = 1/2
  // Wall time of the step's parts, s (steady clock; where a run's time goes, not a result:
  // never in a checkpoint). The rest of the step (free velocities, energy account, position
  // update, contact list) is step time minus these three.
  double detection_s = 0.0;   // candidate table refresh + gaps, normals, warm start
  double solve_s = 0.0;       // the velocity-level contact solve
  double correction_s = 0.0;  // gaps after the step + penetration correction
  // A step retaken in parts after it ended unconverged (NscdParameters::retry_parts; only
  // NscdIntegrator::step(double) sets these): the parts of the try that stands (0: the step
  // stood as first taken), and the sweeps of the tries thrown away (their time is in the three
  // times above).
  int retry_parts = 0;
  std::int64_t discarded_sweeps = 0;
  // The parts the step was first taken in, kept from an earlier retry
  // (NscdParameters::retry_keep_steps; 0: whole). A retry goes on from them.
  int start_parts = 0;
  // Retaken at fall_tolerance as a collapse (ToleranceSchedule::begin_collapse; retry_parts is
  // then 1 unless parts followed).
  bool collapse = false;
  // The solve's later stages, if its solver has them (a step taken in parts: the parts' sums;
  // a step retaken: the try that stands, the thrown-away tries' in MechanicsStats::fallback).
  FallbackCounts fallback;
  // Given up at a request (StepInterrupt.h; only NscdIntegrator::step(double) sets it): the
  // state, the counters and the time are back at the step's start, as if it had not been
  // taken, and the other fields mean nothing.
  bool interrupted = false;
};

// One report for a step taken as two halves (NscdIntegrator::step: a step too long for the
// periods): sums of the work and energies, the worse of the flags and residuals, the second
// half's state (candidates, contacts), and its tolerance unless only the first half is
// unconverged: an unconverged report names the tolerance that was missed.
StepReport merged(const StepReport& first, const StepReport& second);

struct MechanicsStats {
  std::int64_t steps = 0;
  std::int64_t total_sweeps = 0;
  int max_sweeps = 0;                  // "max_iterations" in the run summary
  std::int64_t unconverged_steps = 0;
  std::int64_t stalled_steps = 0;      // of the unconverged ones, stopped early for no progress
  // Steps solved at the tolerance schedule's fall_tolerance (ToleranceSchedule.h), and of
  // those the unconverged ones (also counted in unconverged_steps: a step is converged when it
  // met the tolerance in force at that step).
  std::int64_t fall_steps = 0;
  std::int64_t fall_unconverged_steps = 0;
  // Steps retaken at fall_tolerance as a collapse (ToleranceSchedule::begin_collapse).
  std::int64_t collapse_steps = 0;
  double max_penetration_m = 0.0;
  // Siconos' residual (StepReport::siconos_residual): the largest, and the steps where it was
  // above the tolerance in force (whether or not the solver's own test passed).
  double max_siconos_residual = 0.0;
  std::int64_t siconos_unconverged_steps = 0;
  double max_natural_map_residual = 0.0;  // the largest StepReport::natural_map_residual
  std::int64_t correction_sweeps = 0;  // sum of the steps' correction_sweeps
  // Steps taken as two halves because particles could move apart across the periods by more
  // than the periods allow (NscdIntegrator::step); each half counts in `steps`.
  std::int64_t halved_steps = 0;
  // Steps taken in 2^k equal parts (k <= NscdIntegrator::kMaxHalvings) because a moving wall
  // that can touch a particle was fast enough to travel more than the largest radius within the
  // step (a landing piston; NscdIntegrator::step); each part counts in `steps`.
  std::int64_t landing_halved_steps = 0;
  // Steps that ended unconverged and were taken again from their start in parts
  // (NscdParameters::retry_parts; each part of the try that stands counts in `steps`), and the
  // sweeps of the tries thrown away (not in total_sweeps; their time is in the times below).
  std::int64_t retried_steps = 0;
  std::int64_t discarded_sweeps = 0;
  // Steps started in the parts an earlier retry needed (NscdParameters::retry_keep_steps; each
  // part counts in `steps`).
  std::int64_t kept_parts_steps = 0;
  // Steps whose table, listed with a piston's likely reach, was listed again with the bound
  // after the solve (StepReport::relisted; each part counts).
  std::int64_t relisted_steps = 0;
  // Steps asked of NscdIntegrator::step(h) (the caller's steps) that ended unconverged: a step
  // taken in parts (landing, periods, retry) counts once here, where unconverged_steps counts
  // each unconverged part. The run's warnings are one per such step.
  std::int64_t unconverged_time_steps = 0;
  // Corrections in which the pistons took their share: the penetration correction with them
  // held could not move what it corrects (particles pinned under a piston; NscdIntegrator::step).
  std::int64_t piston_corrections = 0;
  // The length of the last step taken (a part's, after a step taken in parts), s; 0 before the
  // first. The warm start of a longer step reads it (NscdIntegrator::setup_contacts).
  double last_step_s = 0.0;
  double correction_potential_J = 0.0; // sum of the steps' correction_potential_J
  double max_travel_m = 0.0;           // largest of the steps' max_travel_m
  double energy_change_J = 0.0;          // sums of the steps' energy accounts (StepReport)
  double contact_dissipation_J = 0.0;
  double numerical_dissipation_J = 0.0;
  double detection_s = 0.0;             // sums of the steps' part times (StepReport), s; since
  double solve_s = 0.0;                 //   this process started stepping (a restart counts
  double correction_s = 0.0;            //   from the restart, as the run's wall time does)
  // The contact solver's later stages over every try, thrown away or kept (its seconds since
  // this process started stepping, as the times above).
  FallbackCounts fallback;

  double mean_sweeps() const {         // "mean_iterations" in the run summary
    return steps > 0 ? static_cast<double>(total_sweeps) / static_cast<double>(steps) : 0.0;
  }
  void add(const StepReport& report);
};

}  // namespace tmdem::mechanics
