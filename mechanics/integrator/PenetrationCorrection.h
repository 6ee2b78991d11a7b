#pragma once
// Split-impulse penetration correction ("pseudo-velocity", as Bullet's split impulse and
// Box2D's position solver): a position-only step after the velocity step, whose velocity is
// thrown away, so that removing an overlap never becomes kinetic energy.
//
// Given the gaps g'_c of the contacts after the position update (normals and Delassus blocks
// of the step's velocity problem), find pseudo-impulses s_c >= 0 (frictionless, normal only)
// and pseudo-velocities v~ = M^-1 H_n s such that, for every contact,
//   U~_c = n_c . (v~_i - v~_j) + b_c >= 0,  s_c >= 0,  s_c U~_c = 0,
//   b_c = (g'_c + a_c) / h   (b_c >= -recovery_speed when a recovery speed is set),
// then move q <- q + h v~ and discard v~. With a slop s, overlaps up to 2 s are held; the
// step runs only when some overlap is deeper than 2 s ("triggered"), and then brings each
// triggered contact back to s (a_c = s) while letting the others go as deep as 2 s (a_c = 2 s).
// The factor 2 is hysteresis: correcting to s leaves every corrected contact a band of s to
// absorb the next steps' solver error and its neighbours' corrections; without it every
// contact sat at the trigger depth and each correction rippled through the whole pile.
// Measured on 300 spheres poured in 3D (mechanics.tolerance 1e-4, 400 steps, 51,000-74,000
// velocity sweeps): 112,590 position sweeps with trigger = target = s solved to 1e-4;
// 64,941 with the band; 8,089 with the band solved to 1e-2. Normal impulses on spheres exert no torque,
// so only centres move. The problem starts from zero every step: nothing is carried over
// (restarts need no extra state), and when nothing is deeper than 2 s nothing is solved.
//
// Walls stay where they are, pistons (walls with a mass) included, unless the caller asks the
// pistons to move (move_pistons): then each takes its share by its inverse mass, along its
// normal, as in the velocity problem. NscdIntegrator asks only when a correction with the
// pistons held left half the depth beyond the trigger or more, so could not move what it
// corrects: a piston that ends a step inside a column standing on the floor can only be pushed
// back itself (held, it stayed 5% of a radius into a column of 6 spheres for good, the
// correction sharing that depth out as overlaps of up to 1.4% of a radius). Moved by every
// correction (at its true mass, or weighed as the heaviest sphere), `periodic_pressed`'s
// piston was lifted again and again and fell back under its load: not at rest within 300 s,
// against 66 s held. correct() moves the particles, and the caller the pistons, by h times
// pseudo_velocity().
//
// Solved by Gauss-Seidel ("nlgs" with mu = 0, a frictionless LCP, which always converges),
// whatever mechanics.solver is, so that no solver's carried state is disturbed, to a relative
// residual of kTolerance (or mechanics.tolerance if looser): an error of 1% leaves 1% of the
// corrected depth, which the next correction takes. Its sweeps visit every candidate only every
// NscdParameters::correction_full_sweep_every sweeps (8), and in between the contacts the last
// full sweep left closed (ActiveContactSet.h): a correction pushes a few hundred contacts of a
// bed's tens of thousands, and the rest only need checking. On a deposited 10,000 bed solved
// at the fall tolerance (before a fall needed NscdParameters::fall_share; every step corrected,
// 1 thread) full sweeps took 17.4 s of its 129 s (121 steps, 144 ms a step);
// active-set sweeps 9.4 s of 81 s (a trajectory of 100 steps, 94 ms a step: corrections differ
// within their tolerance, and so does the bed). Active-set sweeps run on one thread: on 2
// threads the full slab sweeps had taken 8.8 s (72 ms a step) and these take 9.5 s (94 ms).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class PenetrationCorrection {
 public:
  static constexpr double kTrigger = 2.0;     // correct when deeper than kTrigger slops
  static constexpr double kTolerance = 1e-2;  // relative residual of the position solve

  explicit PenetrationCorrection(const SolverSettings& settings);

  // gap_m: per contact of `problem`, after the position update, m. Moves position (m) of the
  // particles with inverse_mass > 0 in place (not the pistons, even with move_pistons: see
  // pseudo_velocity()). Returns the solve's report (0 sweeps and converged when nothing was
  // deeper than kTrigger slops).
  SolveReport correct(const ContactProblem& problem, const std::vector<double>& gap_m,
                      double slop_m, double recovery_speed_m_per_s, double h_s,
                      std::vector<Eigen::Vector3d>& position, bool move_pistons = false);

  // Pseudo-velocities of the last correct() that solved something (m/s per body, the problem's
  // bodies: particles, then walls): particle i moved by h_s * pseudo_velocity()[i] when its
  // inverse mass is > 0; a piston's entry is along its normal, for the caller to apply.
  const std::vector<Eigen::Vector3d>& pseudo_velocity() const { return velocity_; }

 private:
  std::unique_ptr<ContactSolver> solver_;
  ContactProblem problem_;                      // the velocity problem's geometry, mu = 0
  std::vector<Eigen::Vector3d> impulse_;        // pseudo-impulses, N s (normal part only)
  std::vector<Eigen::Vector3d> velocity_, angular_velocity_;  // pseudo-velocities
};

}  // namespace tmdem::mechanics
