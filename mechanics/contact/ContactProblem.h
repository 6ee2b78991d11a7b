#pragma once
// One step's contact problem, apart from any solver (Siconos style): find local reaction
// impulses r_c (N s, in the frame n, t1, t2 of contact c) such that each contact obeys the
// bipotential Coulomb law (CoulombCone.h) with its local velocity
//   U_c = H_c^T v + bias_c n,   v = v_free + M^-1 H r   (all contacts together).
// H_c maps a local impulse to the two bodies' velocity changes; W = H^T M^-1 H is the
// Delassus operator, whose diagonal block for two spheres is diag(w_n, w_t, w_t) exactly.
//
// The problem is built by NscdIntegrator and only read by the solvers (ContactSolver.h); the
// kinematics of one contact (U_c, applying r_c, the rolling pair) are ContactKinematics.h.
// Everything is a structure of arrays reused from step to step: no allocation once warm.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <array>
#include <vector>

#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {

struct ContactProblem {
  int dimension = 3;  // 2: reactions stay in the xy-plane (t2 = z, r_t2 = 0)

  // Bodies: the particles, then one per wall (body particle_count + w for wall w). A wall body
  // has inverse mass 0 unless it is a piston, no rotation, and its velocity stays along its
  // normal, which for a plane is the normal of every contact it has: a piston's inverse mass
  // adds to w_n of its contacts and the Delassus blocks stay diag(w_n, w_t, w_t).
  std::size_t particle_count = 0;
  std::vector<double> inverse_mass;                     // 1/kg, 0 for fixed particles and walls
  std::vector<double> inverse_inertia;                  // 1/(kg m^2), 0 for fixed particles
  std::vector<Eigen::Vector3d> free_velocity;           // m/s, v + h M^-1 F_ext
  std::vector<Eigen::Vector3d> free_angular_velocity;   // rad/s

  // Contacts.
  std::vector<std::int32_t> body_i;     // particle
  std::vector<std::int32_t> body_j;     // particle, or wall_code(wall) (PairIndex.h; body wall_body(j))
  std::vector<Eigen::Vector3d> normal;  // unit, from j to i
  std::vector<Eigen::Vector3d> tangent1, tangent2;
  std::vector<double> lever_i, lever_j; // m, contact point offsets (radii; 0 for a wall)
  std::vector<double> w_n, w_t;         // Delassus block diag(w_n, w_t, w_t), 1/kg
  std::vector<double> bias;             // m/s, position term added to the normal velocity
  std::vector<double> mu;               // friction coefficient
  // Normal compliance (MechanicsNormalLaw "hertz"; `compliant` false: rigid, the array is not
  // sized). Contact c's normal velocity is then U_n = H_c^T v + bias + compliance_c r_n, 1/kg:
  // the Moreau-Jean step of an elastic normal spring of stiffness k, compliance 1 / (k h^2)
  // (HertzNormalLaw.h). W becomes W + diag(compliance_c, 0, 0): positive definite, so the
  // reactions of a hyperstatic packing are unique. Every solver sees it through
  // normal_delassus(c) (its local block) and contact_velocity() (ContactKinematics.h).
  bool compliant = false;
  std::vector<double> compliance;       // 1/kg (m/s per N s)
  // m/s; 0: off. The Gauss-Seidel stop test (GaussSeidelUpdate.h) counts a contact's impulse
  // |r_c| at most as the impulse that would give its bodies this speed, stop_speed / w_n: the
  // test is relative to the reactions (scale-free) where they carry weight, and relative to
  // this speed where they carry a load far above it. Why: under a piston a contact's impulse
  // is hundreds of weight impulses, a relative error of 1e-5 on it moves the bodies by 1e-5 of
  // that impulse's speed every step, and the loaded bed creeps (NscdParameters::
  // stop_travel_fraction).
  double stop_speed = 0.0;

  // Rolling resistance (Material::rolling_friction; off when `rolling` is false, and then the
  // three arrays below are not sized). Each contact also carries a rolling angular impulse m_c
  // (N m s, global, perpendicular to n), acting as +m_c on i and -m_c on j, against the
  // relative spin omega_i - omega_j (its part perpendicular to n: rolling; the spin about n,
  // "twisting", is left free). Law (Coulomb-like rolling cone, "model A / constant directional
  // torque" of Ai et al. 2011, the NSC rolling friction of Chrono):
  //   |m_c| <= mu_r R_eff r_n,   and  omega_rel,t = 0 (rolling stick) if |m_c| < mu_r R_eff r_n,
  //   otherwise m_c = -mu_r R_eff r_n omega_rel,t / |omega_rel,t| (rolling at the limit).
  // R_eff = R_i R_j / (R_i + R_j) (a wall: R_i). The rolling block of W is w_r I with
  // w_r = 1/I_i + 1/I_j (walls do not rotate).
  bool rolling = false;
  std::vector<double> rolling_limit;    // m, mu_r R_eff: |m_c| <= rolling_limit r_n
  std::vector<double> rolling_radius;   // m, R_eff (scales m_c to an impulse in stop tests)
  std::vector<double> w_r;              // 1/(kg m^2)

  // Optional (empty: not given): where each particle is (m), and the axis (0-2) across which a
  // solver may cut the contacts into slabs that threads sweep at once (ContactSlabs.h).
  // NscdIntegrator gives them: the horizontal axis along which the particles spread widest.
  std::vector<Eigen::Vector3d> particle_position;
  int split_axis = 0;
  // [low, high) of split_axis when it is periodic (m; positions wrapped into it), else {0, 0}:
  // slabs then go round the period (ContactSlabs.h).
  std::array<double, 2> split_period{0.0, 0.0};
  bool split_periodic() const { return split_period[1] > split_period[0]; }

  std::size_t size() const { return body_i.size(); }
  // W_cc's normal entry, 1/kg: w_n, plus the normal compliance of a compliant problem.
  double normal_delassus(std::size_t c) const { return compliant ? w_n[c] + compliance[c] : w_n[c]; }
  std::size_t body_count() const { return inverse_mass.size(); }
  // The body of the wall named by j (is_wall(j)).
  std::size_t wall_body(std::int32_t j) const { return particle_count + wall_index(j); }
  // Sets particle_count and appends `walls` immobile wall bodies (a problem built by hand).
  void add_fixed_wall_bodies(std::size_t walls) {
    particle_count = inverse_mass.size();
    inverse_mass.resize(particle_count + walls, 0.0);
    inverse_inertia.resize(particle_count + walls, 0.0);
    free_velocity.resize(particle_count + walls, Eigen::Vector3d::Zero());
    free_angular_velocity.resize(particle_count + walls, Eigen::Vector3d::Zero());
  }
  void resize_contacts(std::size_t count);
  // Copies every per-contact value of contact c of `from` into slot k (sized already), its
  // bodies named as in `from`: a solver's reordered copy of a problem.
  void copy_contact(std::size_t k, const ContactProblem& from, std::size_t c);

  // A contact between two immobile bodies carries no reaction (W_cc = 0).
  bool solvable(std::size_t c) const { return w_n[c] > 0.0; }

  // velocity = v_free + M^-1 H r for all reactions at once (the start of any solver, and the
  // W r product of a Jacobi-type method: U(r) - U(0)).
  void velocities_from_reactions(const std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) const;

  // angular_velocity += sum_c W m_c over all contacts (after velocities_from_reactions).
  void add_rolling_impulses(const std::vector<Eigen::Vector3d>& m,
                            std::vector<Eigen::Vector3d>& angular_velocity) const;
  // The start of every Gauss-Seidel solve: velocities_from_reactions, plus the rolling
  // impulses m when the problem has rolling resistance (m is not read otherwise).
  void velocities_from_reactions(const std::vector<Eigen::Vector3d>& r,
                                 const std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) const {
    velocities_from_reactions(r, velocity, angular_velocity);
    if (rolling) add_rolling_impulses(m, angular_velocity);
  }
};

inline void ContactProblem::copy_contact(std::size_t k, const ContactProblem& from, std::size_t c) {
  body_i[k] = from.body_i[c];
  body_j[k] = from.body_j[c];
  normal[k] = from.normal[c];
  tangent1[k] = from.tangent1[c];
  tangent2[k] = from.tangent2[c];
  lever_i[k] = from.lever_i[c];
  lever_j[k] = from.lever_j[c];
  w_n[k] = from.w_n[c];
  w_t[k] = from.w_t[c];
  bias[k] = from.bias[c];
  mu[k] = from.mu[c];
  if (from.compliant) compliance[k] = from.compliance[c];
  if (from.rolling) {
    rolling_limit[k] = from.rolling_limit[c];
    rolling_radius[k] = from.rolling_radius[c];
    w_r[k] = from.w_r[c];
  }
}

}  // namespace tmdem::mechanics
