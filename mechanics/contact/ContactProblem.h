#pragma once
// One step's contact problem, apart from any solver (Siconos style): find local reaction
// impulses r_c (N s, in the frame n, t1, t2 of contact c) such that each contact obeys the
// bipotential Coulomb law (CoulombCone.h) with its local velocity
//   U_c = H_c^T v + bias_c n,   v = v_free + M^-1 H r   (all contacts together).
// H_c maps a local impulse to the two bodies' velocity changes; W = H^T M^-1 H is the
// Delassus operator, whose diagonal block for two spheres is diag(w_n, w_t, w_t) exactly.
//
// The problem is built by NscdIntegrator and only read by the solvers (ContactSolver.h).
// Everything is a structure of arrays reused from step to step: no allocation once warm.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cassert>
#include <cstddef>
#include <cstdint>
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

  std::size_t size() const { return body_i.size(); }
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

  // Local velocity U_c = H_c^T v (+ bias along n) in (n, t1, t2), m/s; t2 is 0 in 2D.
  Eigen::Vector3d local_velocity(std::size_t c, const std::vector<Eigen::Vector3d>& velocity,
                                 const std::vector<Eigen::Vector3d>& angular_velocity) const;

  // The normal component of local_velocity, m/s: n . (v_i - v_j) + bias (the spin terms
  // (R_i w_i + R_j w_j) x n are perpendicular to n and drop out).
  double normal_velocity(std::size_t c, const std::vector<Eigen::Vector3d>& velocity) const {
    const std::int32_t j = body_j[c];
    const Eigen::Vector3d& vj = is_wall(j) ? velocity[wall_body(j)] : velocity[j];
    return (velocity[body_i[c]] - vj).dot(normal[c]) + bias[c];
  }

  // velocity += M^-1 H_c r_c for one local impulse r_c.
  void apply_impulse(std::size_t c, const Eigen::Vector3d& r_local,
                     std::vector<Eigen::Vector3d>& velocity,
                     std::vector<Eigen::Vector3d>& angular_velocity) const;

  // velocity = v_free + M^-1 H r for all reactions at once (the start of any solver, and the
  // W r product of a Jacobi-type method: U(r) - U(0)).
  void velocities_from_reactions(const std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) const;

  // Rolling (only when `rolling`): the relative spin omega_i - omega_j of contact c without
  // its component along n, rad/s; and angular_velocity += W m for a rolling impulse m.
  Eigen::Vector3d rolling_velocity(std::size_t c,
                                   const std::vector<Eigen::Vector3d>& angular_velocity) const {
    Eigen::Vector3d w = angular_velocity[body_i[c]];
    if (!is_wall(body_j[c])) w -= angular_velocity[body_j[c]];
    return w - w.dot(normal[c]) * normal[c];
  }
  void apply_rolling_impulse(std::size_t c, const Eigen::Vector3d& m,
                             std::vector<Eigen::Vector3d>& angular_velocity) const {
    angular_velocity[body_i[c]] += inverse_inertia[body_i[c]] * m;
    if (!is_wall(body_j[c])) angular_velocity[body_j[c]] -= inverse_inertia[body_j[c]] * m;
  }
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

  // Global impulse of a local one, N s.
  Eigen::Vector3d to_global(std::size_t c, const Eigen::Vector3d& r_local) const {
    return r_local[0] * normal[c] + r_local[1] * tangent1[c] + r_local[2] * tangent2[c];
  }
};

// Inline: the inner loop of every solver.
inline Eigen::Vector3d ContactProblem::local_velocity(
    std::size_t c, const std::vector<Eigen::Vector3d>& velocity,
    const std::vector<Eigen::Vector3d>& angular_velocity) const {
  // Velocity of i's material point at the contact minus j's: contact points sit at
  // x_i - R_i n and x_j + R_j n.
  const Eigen::Vector3d& n = normal[c];
  const std::int32_t i = body_i[c], j = body_j[c];
  Eigen::Vector3d u;
  if (!is_wall(j)) {
    u = velocity[i] - velocity[j] - (lever_i[c] * angular_velocity[i] + lever_j[c] * angular_velocity[j]).cross(n);
  } else {
    assert(wall_body(j) < velocity.size() && "a wall contact needs its wall body (add_fixed_wall_bodies)");
    u = velocity[i] - velocity[wall_body(j)] - (lever_i[c] * angular_velocity[i]).cross(n);
  }
  return Eigen::Vector3d(u.dot(n) + bias[c], u.dot(tangent1[c]),
                         dimension == 2 ? 0.0 : u.dot(tangent2[c]));
}

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
  if (from.rolling) {
    rolling_limit[k] = from.rolling_limit[c];
    rolling_radius[k] = from.rolling_radius[c];
    w_r[k] = from.w_r[c];
  }
}

inline void ContactProblem::apply_impulse(std::size_t c, const Eigen::Vector3d& r_local,
                                   std::vector<Eigen::Vector3d>& velocity,
                                   std::vector<Eigen::Vector3d>& angular_velocity) const {
  // p acts on i at x_i - R_i n (torque -R_i n x p) and -p on j at x_j + R_j n (same sign).
  const Eigen::Vector3d p = to_global(c, r_local);
  const Eigen::Vector3d nxp = normal[c].cross(p);
  const std::int32_t i = body_i[c], j = body_j[c];
  velocity[i] += inverse_mass[i] * p;
  angular_velocity[i] -= (inverse_inertia[i] * lever_i[c]) * nxp;
  if (!is_wall(j)) {
    velocity[j] -= inverse_mass[j] * p;
    angular_velocity[j] -= (inverse_inertia[j] * lever_j[c]) * nxp;
  } else if (const std::size_t b = wall_body(j); inverse_mass[b] > 0.0) {
    velocity[b] -= (inverse_mass[b] * r_local[0]) * normal[c];  // a piston: along n only
  }
}

}  // namespace tmdem::mechanics
