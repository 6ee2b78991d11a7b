#pragma once
// Non-smooth contact dynamics (Moreau-Jean theta scheme, [MOR 94][JEA 99]) with the
// bipotential contact law solved by nonlinear Gauss-Seidel ("equilibres successifs").
//
// One step of length h:
//   1. refresh the candidate table if needed (ContactDetector);
//   2. free velocities v_free = v + h M^-1 F_ext (gravity; no torque);
//   3. for each candidate: local frame (n from j to i, tangents), Delassus block
//      W = H^T M^-1 H, and the position term of the Signorini condition (below);
//   4. the contact solver chosen by name (ContactSolverRegistry.h; "nlgs": Gauss-Seidel sweeps,
//      each contact solving its own law with the others frozen), warm-started from the
//      previous step's forces of the same pair;
//   5. q_{n+1} = q_n + h (theta v_{n+1} + (1 - theta) v_n);
//   6. penetration correction by positions only (split impulse, PenetrationCorrection.h).
//
// Signorini, activated by the predicted gap. Let g be the gap at the start of the step and
// P = g + h (1 - theta) u_n(v_n) the gap predicted with the part of the position update that
// is already known. The normal condition is applied to U_n = u_n(v_{n+1}) + max(P, 0) / h:
//   U_n >= 0, r_n >= 0, r_n U_n = 0   (inside the bipotential law, u_n is replaced by U_n).
// For P >= 0 this keeps P >= 0 from step to step, hence g_{n+1} >= (1 - theta) P >= 0 (for
// spheres the linearised gap is a lower bound of the true one): a contact reached at P = 0
// ends with u_n = 0 (inelastic impact), a resting contact (g = 0, u = 0) carries exactly the
// weight, and far candidates (P > 0) only act if they would close. An overlap (P < 0, from
// solver error or an initial overlap) only gets u_n >= 0: it may not deepen, and it is never
// pushed out by the velocity. Pushing it out there (bias P / h, as before) turned an overlap
// d into a speed d / h (1e-6 m in 1e-3 s = 1e-3 m/s), so solver error alone kept piles
// moving. Instead step 6 moves the centres apart (pseudo-velocities that are thrown away)
// when an overlap is deeper than twice the slop (NscdParameters::penetration_slop_fraction),
// back to the slop: no velocity, no energy is ever made of an overlap.
//
// Pistons (Wall.h: a plane wall with a mass) are bodies of the contact problem with one
// translational degree of freedom along their normal n_w: free velocity
// v + h (load / m + g.n_w) n_w, their inverse mass in w_n of their contacts (exact, no
// penalty), and the same theta update of their point as the particles. The candidate table
// follows their motion (ContactDetector.h); max_speed and the energies include them.
//
// Energy account of a step. With M (v+ - v-) = h F_gravity + sum_c H_c r_c and the position
// update above, kinetic plus gravitational energy change exactly by
//   dK + dV = sum_c r_c . u_theta,c - (theta - 1/2) |v+ - v-|_M^2,
// u_theta,c = theta u_c(v+) + (1 - theta) u_c(v-) the contact's relative velocity (no bias).
// So D_c = -r_c . u_theta,c is what contact c dissipated (slip work plus impact loss; >= 0
// except where a penetration beyond the slop is pushed out, which does work), and
// (theta - 1/2) |v+ - v-|_M^2 is the scheme's own numerical damping (0 for theta = 1/2, > 0
// above). StepReport carries the three terms; ContactForce::dissipated_power_W is D_c / h.
// A piston counts as a body: its kinetic energy, and its load plus weight as a constant
// external force whose potential is -F . x.
//
// Friction between two materials uses the smaller coefficient (see Material.h), and so does
// rolling resistance: with rolling_friction > 0 each contact also carries a rolling angular
// impulse bounded by mu_r R_eff r_n (ContactProblem.h), solved with the (n, t) block in the
// same Gauss-Seidel visit; its work -m . (theta w_rel+ + (1 - theta) w_rel-) counts in D_c.
// dimension 2: gravity, reactions and velocities are kept in the xy-plane exactly
// (z, v_z, omega_x, omega_y stay as they are: 0 for a planar scene); spheres still roll.
// Fixed particles have infinite mass and inertia: they never move and keep zero velocity.

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include <memory>

#include "mechanics/detection/ContactDetector.h"
#include "mechanics/contact/ContactForce.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/model/Material.h"
#include "mechanics/integrator/MechanicsState.h"
#include "mechanics/integrator/NscdParameters.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/integrator/PenetrationCorrection.h"
#include "mechanics/solvers/SpatialContactOrder.h"
#include "mechanics/integrator/StepReport.h"
#include "mechanics/integrator/ToleranceSchedule.h"
#include "mechanics/model/Wall.h"

namespace tmdem::mechanics {

class NscdIntegrator {
 public:
  // Throws std::invalid_argument for inconsistent input (bad material index, non-positive
  // step, theta outside (0, 1], dimension not 2 or 3, ...).
  NscdIntegrator(ParticleSet particles, std::vector<Material> materials, std::vector<Wall> walls,
                 const Eigen::Vector3d& gravity_m_per_s2, int dimension,
                 NscdParameters parameters = {});

  StepReport step();          // one step of parameters().time_step
  // One step of h seconds. On a periodic scene where two particles could move apart across the
  // periods by more than they allow within h (a landing piston kicking spheres sideways), the
  // step is taken as two halves, and so on down to 2^-kMaxHalvings of the time step; beyond,
  // the detector stops the run with an error naming the lengths. A step in which a moving wall
  // that can touch a particle is fast enough to travel more than the largest radius (a piston
  // landing at metres per second) is taken in 2^k equal parts, the fewest that fit, k at most
  // kMaxHalvings (beyond, each part lists the pairs within the wall's reach). A step that ends
  // unconverged is taken again from its start in 2, 4, ... equal parts, up to
  // NscdParameters::retry_parts, until all its parts converge; the last try stands. With
  // NscdParameters::retry_keep_steps the steps after such a retry start in its parts.
  StepReport step(double h);
  static constexpr int kMaxHalvings = 4;  // a step is halved at most this many times
  // A moving wall's load reach 2 h^2 |a|, in the detector's widest margins, beyond which its
  // candidates are listed with its likely reach (NscdParameters::estimate_wall_reach).
  static constexpr double kEstimatedReachFrom = 2.0;
  // Converged steps in a row that double back the parts a retry may go up to, after a step that
  // stayed unconverged through its retries halved them (step(double); NscdParameters::retry_parts).
  static constexpr int kRetryRecoverSteps = 10;
  // Penetration correction passes at most in a part of a landing taken in parts, and the overlap
  // (in penetration slops) a pass must leave for another (step()).
  static constexpr int kCorrectionPasses = 4;
  static constexpr double kDeepOverlapSlops = 100.0;

  // Contacts with r_n > 0 after the last step (forces are the step means, impulse / h), in
  // strictly increasing (i, j) order, j signed (walls first for each i), as the candidates are.
  // The coupling relies on this order (gather_contacts does not sort).
  const std::vector<ContactForce>& contacts() const { return contacts_; }
  const MechanicsStats& stats() const { return stats_; }
  void restore_stats(const MechanicsStats& stats) { stats_ = stats; }  // after a restart

  // Called at the end of every step(h) that was not given up, with h (s) and the step's report
  // (its parts' sums when taken in parts; the try that stands when retaken): a per-step log
  // (the coupling's MechanicsStepLog). Nothing about the step depends on it. Empty: none.
  using StepObserver = std::function<void(double h_s, const StepReport& report)>;
  void set_step_observer(StepObserver observer) { step_observer_ = std::move(observer); }

  // What the next step reads (MechanicsState.h), and putting it back into an integrator built
  // from the same scene: the steps after restore_state(save_state()) are bitwise those of the
  // saved integrator. Both in NscdIntegratorState.cpp. restore_state throws
  // std::invalid_argument when the particle or candidate counts do not fit.
  MechanicsState save_state() const;
  // The same into `state`, reusing its storage (the retry of an unconverged step saves every
  // step's start: no allocation once the vectors have grown).
  void save_state(MechanicsState& state) const;
  void restore_state(const MechanicsState& state);

  double kinetic_energy() const;    // J, translation + rotation of moving particles
  // J, -sum m g.x (zero at the origin), moving particles. Gravity along a periodic axis makes it
  // jump by m g L where a particle wraps; StepReport's energy account sums displacements instead.
  double potential_energy() const;
  // Largest centre speed |v| of a moving particle, m/s; the "settle" phase ends when it
  // drops below settle_velocity. Spin is left out on purpose: a sphere spinning about its
  // contact normal is at rest as far as the packing goes, and point contacts never stop it.
  double max_speed() const;
  // The speed the tolerance schedule judges a fall on, m/s: the fall_share quantile of the
  // moving particles' centre speeds (the k-th largest, k = max(1, ceil(fall_share n))), or a
  // moving wall's speed if larger.
  double fall_judged_speed() const;
  // The speed at or above which piston `wall` compacts the bed (NscdParameters::compaction_speed;
  // automatic: compaction_fraction of the speed its load and weight give it over a step of h
  // seconds, h |F / m + g.n|), m/s; 0 for a fixed wall, when off, or with a solver that does not
  // stop on Siconos' residual (NscdParameters::compaction_speed).
  double compaction_speed_m_per_s(std::size_t wall, double h) const;
  // Whether a piston moves at or above its compaction speed: the tolerance schedule's fall.
  bool piston_compacting(double h) const;

  const ParticleSet& particles() const { return particles_; }
  // Mutable access (e.g. restoring a checkpoint). Call invalidate_contacts() after moving
  // particles by hand; velocities can be changed freely.
  ParticleSet& particles() { return particles_; }
  void invalidate_contacts();

  // Walls as they are now (a piston's point and velocity change with every step).
  const std::vector<Wall>& walls() const { return walls_; }
  // Changes the imposed force of piston `wall`, N (throws for a fixed wall or a non-finite load).
  void set_piston_load(std::size_t wall, double load_N);
  // Overlaps the bed starts with that belong to the packing (an imported bed made at a softened
  // modulus, LIGGGHTS' 4% of a radius): call before the first step. Every pair that overlaps at
  // the first step, of two particles with holds[i] != 0 (or one and a wall), keeps its overlap:
  // the position step (PenetrationCorrection.h) reads its gap as gap + held, so it never pushes
  // it out, and the held overlap only shrinks, to the pair's overlap after each step, gone once
  // the pair opens. Without it the position step pushes every such pair apart in the first
  // step, and the whole bed expands and falls back (liggghts_import: 131 steps of up to 10,000
  // sweeps). holds: one per particle.
  void hold_initial_overlaps(std::vector<std::uint8_t> holds);
  // Pairs whose overlap is held now, and the largest held overlap, m.
  std::size_t held_overlaps() const;
  double largest_held_overlap_m() const;
  const std::vector<Material>& materials() const { return materials_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }
  int dimension() const { return dimension_; }
  const NscdParameters& parameters() const { return parameters_; }
  const ContactDetector& detector() const { return detector_; }
  // The last step's contact problem and its solver (mechanics.solver).
  const ContactProblem& problem() const { return problem_; }
  const ContactSolver& solver() const { return *solver_; }
  // The last step's local reaction impulses (n, t1, t2), N s, one per contact of problem(), in
  // its order: the solution of problem() the step used (the rolling impulses are not included).
  const std::vector<Eigen::Vector3d>& reactions() const { return reactions_; }
  // The tolerance schedule (mechanics.fall_tolerance, fall_speed; ToleranceSchedule.h): its
  // phase, and the step that first used the tight tolerance after the fall.
  const ToleranceSchedule& tolerance_schedule() const { return schedule_; }
  // The solver tolerance the last step used (the scene's tolerance before the first step).
  double tolerance_in_force() const { return solver_settings_.tolerance; }

 private:
  // A piston's free acceleration along its normal, m/s^2: its load and weight over its mass.
  double piston_acceleration_m_per_s2(const Wall& piston) const {
    return piston.load_N / piston.mass_kg + gravity_.dot(piston.normal);
  }
  // bound_only: every moving wall listed with its bound (relist_with_bound).
  void refresh_candidates(double h, bool bound_only = false);
  // With NscdParameters::estimate_wall_reach: the reach each moving wall's pairs (and, once it
  // is engaged, the particles') are listed with, from the net push the bed left it last step
  // (wall_listing_lookahead_); listing_estimated_ when any is below the bound wall_lookahead_.
  void estimate_wall_reach(double h);
  // Whether the table covers the step's travel (the velocities just solved), and the step's
  // problem listed again with the bound when it did not (estimate_wall_reach).
  bool listing_covers_travel(double h);
  void relist_with_bound(double h);
  // periodic_lookahead_ for a step of h (periodic scenes; step() fills it before
  // refresh_candidates reads it).
  void fill_periodic_lookahead(double h);
  // lookahead_ for a step of h s (refresh_candidates).
  void fill_lookahead(double h);
  // step(h); landing_parts: a landing may be taken in parts (false inside its parts).
  StepReport step(double h, bool landing_parts);
  // step(h) before its count of unconverged time steps: the first try, and its retries in parts.
  StepReport step_with_retries(double h);
  // `parts` steps of part_s each, one merged report (a landing's parts, a retry's).
  StepReport step_in_parts(double part_s, int parts, bool landing_parts);
  // Whether a moving wall that can touch a particle within a step of h s moves fast enough to
  // carry it more than the largest radius in it (2 h |v| against
  // ContactDetector::wall_reach_exceeds_margin): step() then takes the step in equal parts. For
  // such a wall it sets the walls' look-aheads and lookahead_ for h (the step sets them again).
  bool wall_lands_too_fast(double h);
  void setup_contacts(double h);
  // The "hertz" normal law (NscdIntegratorHertz.cpp): each solvable candidate's compliance and
  // bias from its linearised Hertz law, after setup_contacts.
  void set_hertz_laws(double h);
  // gap_m (per candidate, m) += the Hertz overlap of the force of the step just solved: the
  // position step then removes only what lies beyond the elastic overlap.
  void add_elastic_overlaps(double h, std::vector<double>& gap_m) const;
  bool compliant() const { return parameters_.normal_law == NormalLaw::hertz; }
  void keep_in_plane();
  void refresh_wall_bodies(double h);
  // The step's energy change and numerical damping (see above), from v- and v+.
  void account_energy(double h, StepReport& report) const;
  void gaps_after_step(std::vector<double>& gap) const;  // per candidate, current positions, m
  // hold_initial_overlaps: the held overlaps from the first step's gaps (gap_), and each step
  // the held overlaps shrunk to the pairs' overlaps in gap_m (after the step), then added to it.
  void take_initial_overlaps();
  void add_held_overlaps(std::vector<double>& gap_m);
  // The contact solver on problem_ (in a spatial order from parameters_.spatial_order_from).
  SolveReport solve_contacts();
  // The solver at this tolerance from now on (a no-op when it already is).
  void use_tolerance(double tolerance);
  // Whether the solver may hand this try's unconverged solves on to its later stages
  // (NscdParameters::fallback_on_last_try); kept across use_tolerance's new solvers.
  void set_hand_on(bool allowed);
  // The axis across which a solver may cut the contacts into slabs: the horizontal one (not
  // along gravity) along which the particles spread widest.
  int split_axis() const;

  ParticleSet particles_;
  std::vector<Material> materials_;
  std::vector<Wall> walls_;
  Eigen::Vector3d gravity_;
  int dimension_;
  NscdParameters parameters_;
  ContactDetector detector_;

  std::vector<double> inverse_mass_, inverse_inertia_;  // 0 for fixed particles
  // Per body (particles, then walls: ContactProblem.h): start-of-step velocities, and the
  // solver's velocities (copied back to the particles and walls after the solve).
  std::vector<Eigen::Vector3d> old_velocity_, old_angular_velocity_;
  std::vector<Eigen::Vector3d> body_velocity_, body_angular_velocity_;
  std::vector<double> lookahead_;
  std::vector<double> periodic_lookahead_;  // m, along the periodic axes; empty without them
  std::vector<double> wall_lookahead_;  // m; empty when no wall moves
  std::vector<double> wall_listing_lookahead_;  // m; the estimate (estimate_wall_reach)
  std::vector<double> wall_carried_N_;          // N; the bed's push on each wall last step
  bool listing_estimated_ = false;
  std::vector<Eigen::Vector3d> travel_m_;       // the step's travel per particle (the check)
  std::vector<double> wall_travel_m_;           // and per wall, along its normal
  mutable std::vector<double> speed_;   // fall_judged_speed's work space, m/s
  bool has_piston_ = false;
  bool static_start_pending_ = true;  // the next step is the first, and knows no forces
  // hold_initial_overlaps: per particle until the first step takes the overlaps (empty: none
  // to take), and per candidate the overlap held, m (empty when none is held; carried over
  // candidate rebuilds as force_ is).
  std::vector<std::uint8_t> holds_overlap_;
  std::vector<double> held_overlap_;
  std::vector<double> old_held_overlap_;
  double slop_m_ = 0.0;  // penetration slop (NscdParameters), m
  bool in_landing_parts_ = false;  // step() is taking the parts of a landing
  // The start of the step being taken, for its retry (NscdParameters::retry_parts), and the
  // first step's pending work that restore_state() would drop (held overlaps to take).
  MechanicsState retry_start_;
  std::vector<std::uint8_t> retry_holds_overlap_;
  // The retry's budget: a step still unconverged after its retries halves the parts the next
  // retries may go up to (down to 1: none), and kRetryRecoverSteps converged steps in a row
  // double them back (up to retry_parts). 0: retry_parts. Both in MechanicsState.
  int retry_limit_ = 0;
  bool hand_on_ = true;  // set_hand_on()
  int retry_converged_in_a_row_ = 0;
  // The parts the next step starts in, after a retry (NscdParameters::retry_keep_steps; 0 or 1:
  // whole), and the converged steps in a row at them. Both in MechanicsState.
  int start_parts_ = 0;
  int start_parts_converged_in_a_row_ = 0;
  double stop_speed_m_per_s_ = 0.0;  // ContactProblem::stop_speed outside the fall
  ContactProblem problem_;
  std::unique_ptr<ContactSolver> solver_;
  SolverSettings solver_settings_;  // solver_'s, tolerance as in force
  ToleranceSchedule schedule_;
  SpatialContactOrder order_;  // of the candidate table (invalidated when it changes)
  std::vector<Eigen::Vector3d> reactions_;   // local impulse per candidate (n, t1, t2), N s
  std::vector<double> gap_;                  // per candidate at the start of the step, m
  std::vector<double> gap_after_;            // per candidate after the step, m
  std::vector<double> hertz_coefficient_;    // K per candidate, N/m^1.5 ("hertz"; 0: rigid this step)
  PenetrationCorrection correction_{SolverSettings{}};
  std::vector<Eigen::Vector3d> force_;       // global reaction force per candidate, N
  std::vector<Eigen::Vector3d> old_force_;   // same, before a candidate rebuild
  // Rolling resistance (some material has rolling_friction > 0; empty otherwise): rolling
  // angular impulse per candidate (N m s, global, on i), and its mean torque (N m) carried to
  // the next step as the warm start, like force_.
  bool rolling_ = false;
  std::vector<Eigen::Vector3d> rolling_impulse_;
  std::vector<Eigen::Vector3d> torque_, old_torque_;
  std::vector<ContactForce> contacts_;
  MechanicsStats stats_;
  StepObserver step_observer_;
};

}  // namespace tmdem::mechanics
