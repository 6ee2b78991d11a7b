#pragma once
// The kinematics of a contact, written once for every user (ContactProblem's operations, the
// Gauss-Seidel visit, APGD's per-body gather, nncg's conjugate step, NscdIntegrator's
// dissipation, the matrices of the subspace step and of the block solve): the local velocity
// U_c = H_c^T v + bias n in (n, t1, t2), a local impulse applied to the two bodies (velocity +=
// M^-1 H_c r_c, a piston wall body along n only), H_c as matrices (contact_columns,
// contact_rows), and the rolling pair (relative spin perpendicular to n; a rolling impulse
// applied).
//
// Each function is an inline template (declared inline: gcc then inlines them into the visit as
// it did the hand-written code) over the vector type Vec it computes in: Eigen::Vector3d, or
// ScalarVec3 in the Gauss-Seidel visit (why: ScalarVec3.h). Body velocities are always stored
// as Eigen::Vector3d. One expression tree serves both types, and ScalarVec3 rounds every
// operation as Eigen does, so both give the same bits (tests/mechanics/solvers/
// test_gauss_seidel_visit.cpp). Keep the order of every operation: reassociating a sum or
// hoisting a product changes the trajectories' bits.
//
// Geometry: contact points sit at x_i - R_i n on body i and x_j + R_j n on body j (R: lever_i,
// lever_j; 0 for a wall). A local impulse r gives the global p = r_n n + r_t1 t1 + r_t2 t2,
// acting as +p on i at its point (torque -R_i n x p) and -p on j at its point (torque
// -R_j n x p, the same sign).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/contact/ScalarVec3.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {

// v += a and v -= a on a stored vector, for an Eigen operand (ScalarVec3's are in ScalarVec3.h).
template <class Derived>
inline void add_to(Eigen::Vector3d& v, const Eigen::MatrixBase<Derived>& a) {
  v += a;
}
template <class Derived>
inline void subtract_from(Eigen::Vector3d& v, const Eigen::MatrixBase<Derived>& a) {
  v -= a;
}

// Global impulse of a local one, N s.
template <class Vec>
inline Vec global_impulse(const ContactProblem& problem, std::size_t c, const Vec& r_local) {
  const Vec n(problem.normal[c]), t1(problem.tangent1[c]), t2(problem.tangent2[c]);
  return r_local[0] * n + r_local[1] * t1 + r_local[2] * t2;
}

// The order in which relative_velocity adds its terms: the same quantity, other last bits.
enum class VelocityRounding {
  solver,       // (v_i - v_j) - (R_i w_i + R_j w_j) x n: U_c, for every solver
  points_first  // (v_i - R_i w_i x n) - (v_j + R_j w_j x n): each body's material point first.
                // NscdIntegrator's position term (the normal velocity at the start of a step)
                // has always been built on it; built on `solver` instead, the trajectories
                // change in their last bits (first_scene: 104 contacts in the first output
                // instead of 103).
};

// The velocity of i's material point at contact c minus j's, global, m/s (no bias); a wall's
// point moves with its body.
template <class Vec, VelocityRounding rounding = VelocityRounding::solver>
inline Vec relative_velocity(const ContactProblem& problem, std::size_t c,
                             const std::vector<Eigen::Vector3d>& velocity,
                             const std::vector<Eigen::Vector3d>& angular_velocity) {
  const Vec n(problem.normal[c]);
  const std::int32_t i = problem.body_i[c], j = problem.body_j[c];
  const double lever_i = problem.lever_i[c], lever_j = problem.lever_j[c];
  const Vec vi(velocity[i]), wi(angular_velocity[i]);
  assert((!is_wall(j) || problem.wall_body(j) < velocity.size()) &&
         "a wall contact needs its wall body (add_fixed_wall_bodies)");
  if constexpr (rounding == VelocityRounding::points_first) {
    const Vec point_i = vi - (lever_i * wi).cross(n);
    if (is_wall(j)) return point_i - Vec(velocity[problem.wall_body(j)]);
    return point_i - (Vec(velocity[j]) + (lever_j * Vec(angular_velocity[j])).cross(n));
  } else {
    if (is_wall(j)) return vi - Vec(velocity[problem.wall_body(j)]) - (lever_i * wi).cross(n);
    return vi - Vec(velocity[j]) - (lever_i * wi + lever_j * Vec(angular_velocity[j])).cross(n);
  }
}

// Local velocity U_c = H_c^T v (+ bias along n) in (n, t1, t2), m/s; t2 is 0 in 2D.
template <class Vec>
inline Vec local_velocity(const ContactProblem& problem, std::size_t c,
                          const std::vector<Eigen::Vector3d>& velocity,
                          const std::vector<Eigen::Vector3d>& angular_velocity) {
  const Vec n(problem.normal[c]);
  const Vec u = relative_velocity<Vec>(problem, c, velocity, angular_velocity);
  return Vec(u.dot(n) + problem.bias[c], u.dot(Vec(problem.tangent1[c])),
             problem.dimension == 2 ? 0.0 : u.dot(Vec(problem.tangent2[c])));
}

// The normal component of local_velocity, m/s, from the linear velocities alone:
// n . (v_i - v_j) + bias (the spin terms (R_i w_i + R_j w_j) x n are perpendicular to n and
// drop out; the bits may differ from local_velocity's by the round-off of those terms).
inline double normal_velocity(const ContactProblem& problem, std::size_t c,
                              const std::vector<Eigen::Vector3d>& velocity) {
  const std::int32_t j = problem.body_j[c];
  const Eigen::Vector3d& vj = is_wall(j) ? velocity[problem.wall_body(j)] : velocity[j];
  return (velocity[problem.body_i[c]] - vj).dot(problem.normal[c]) + problem.bias[c];
}

// An open candidate that stays open: no reaction (r_c = 0) and not closing (u_n >= 0, from the
// linear velocities alone). Its exact local solution is then 0, so a Gauss-Seidel visit leaves
// it as it is and it adds nothing to a natural-map residual: most candidates of a look-ahead
// detection are such, and the sweeps and the residuals pass them on this test.
[[gnu::always_inline]] inline bool stays_open(const ContactProblem& problem, std::size_t c,
                                              const Eigen::Vector3d& r_c,
                                              const std::vector<Eigen::Vector3d>& velocity) {
  return r_c[0] == 0.0 && r_c[1] == 0.0 && r_c[2] == 0.0 && !(normal_velocity(problem, c, velocity) < 0.0);
}

// A contact's impulse as its bodies take it: p (N s, global) and n x p.
template <class Vec>
struct BodyImpulse {
  Vec p, n_cross_p;
};
template <class Vec>
inline BodyImpulse<Vec> body_impulse(const ContactProblem& problem, std::size_t c, const Vec& r_local) {
  const Vec p = global_impulse(problem, c, r_local);
  return {p, Vec(problem.normal[c]).cross(p)};
}

// The share of body i (+p at x_i - R_i n) and of a particle j (-p at x_j + R_j n): velocity
// (m/s) and angular velocity (rad/s) change by M^-1 of it. inverse_mass 1/kg,
// inverse_inertia 1/(kg m^2), lever m.
template <class Vec>
inline void take_impulse_as_i(const BodyImpulse<Vec>& impulse, double inverse_mass, double inverse_inertia,
                              double lever, Eigen::Vector3d& velocity, Eigen::Vector3d& angular_velocity) {
  add_to(velocity, inverse_mass * impulse.p);
  subtract_from(angular_velocity, (inverse_inertia * lever) * impulse.n_cross_p);
}
template <class Vec>
inline void take_impulse_as_j(const BodyImpulse<Vec>& impulse, double inverse_mass, double inverse_inertia,
                              double lever, Eigen::Vector3d& velocity, Eigen::Vector3d& angular_velocity) {
  subtract_from(velocity, inverse_mass * impulse.p);
  subtract_from(angular_velocity, (inverse_inertia * lever) * impulse.n_cross_p);
}
// The share of a piston wall body j: -r_n n, along its normal only (a wall does not turn).
template <class Vec>
inline void take_impulse_as_piston(double normal_impulse, const Vec& n, double inverse_mass,
                                   Eigen::Vector3d& velocity) {
  subtract_from(velocity, (inverse_mass * normal_impulse) * n);
}

// velocity += M^-1 H_c r_c for one local impulse r_c.
template <class Vec>
inline void apply_impulse(const ContactProblem& problem, std::size_t c, const Vec& r_local,
                          std::vector<Eigen::Vector3d>& velocity,
                          std::vector<Eigen::Vector3d>& angular_velocity) {
  const BodyImpulse<Vec> impulse = body_impulse(problem, c, r_local);
  const std::int32_t i = problem.body_i[c], j = problem.body_j[c];
  take_impulse_as_i(impulse, problem.inverse_mass[i], problem.inverse_inertia[i], problem.lever_i[c],
                    velocity[i], angular_velocity[i]);
  if (!is_wall(j)) {
    take_impulse_as_j(impulse, problem.inverse_mass[j], problem.inverse_inertia[j], problem.lever_j[c],
                      velocity[j], angular_velocity[j]);
  } else if (const std::size_t b = problem.wall_body(j); problem.inverse_mass[b] > 0.0) {
    take_impulse_as_piston(r_local[0], Vec(problem.normal[c]), problem.inverse_mass[b], velocity[b]);
  }
}

// The columns of M^-1 H_c at unit mobilities (inverse mass and inertia 1; a solver scales them
// by the bodies'): column a of linear[side] and angular[side] is the velocity and angular
// velocity change of side 0 (body i) or 1 (body j) under a unit local impulse along axis a (n,
// t1, t2), applied by the functions above. A wall side moves along n only (a piston) and never
// turns. The matrices of the subspace step (ActiveSetSubspaceStep.h) are built from these, so
// they are the kinematics the sweeps apply.
struct ContactColumns {
  Eigen::Matrix3d linear[2], angular[2];
};
inline ContactColumns contact_columns(const ContactProblem& problem, std::size_t c) {
  ContactColumns out;
  const bool wall = is_wall(problem.body_j[c]);
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d unit = Eigen::Vector3d::Zero();
    unit[a] = 1.0;
    const BodyImpulse<Eigen::Vector3d> impulse = body_impulse(problem, c, unit);
    Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
    take_impulse_as_i(impulse, 1.0, 1.0, problem.lever_i[c], v, w);
    out.linear[0].col(a) = v;
    out.angular[0].col(a) = w;
    v.setZero();
    w.setZero();
    if (wall) take_impulse_as_piston(unit[0], Eigen::Vector3d(problem.normal[c]), 1.0, v);
    else take_impulse_as_j(impulse, 1.0, 1.0, problem.lever_j[c], v, w);
    out.linear[1].col(a) = v;
    out.angular[1].col(a) = w;
  }
  return out;
}

// The rows of H_c^T for one particle: the local velocity (n, t1, t2) of contact c that side 0
// (body i) or side 1 (a particle j) gives by its own velocity v and angular velocity omega,
// U = rows (v; omega), everything else at rest (local_velocity without the bias; the t2 row is
// 0 in 2D). Row a is [s f_a^T, R f_a^T N] for the frame vector f_a, s = +1 for i and -1 for j,
// R the side's lever and N the cross-product matrix of n (N w = n x w), so its angular part is
// (R f_a) x n. Mathematically the transpose of contact_columns' [linear; angular]: the same bits
// for the linear part, to round-off for the angular one (there -(R (n x f_a)) is rounded).
// Computed as a matrix product, not with cross(): a block solve's Delassus entries
// (BodyContactBlock.cpp) have always been built on this product, and the two differ in the
// signs of their zeros, which could reach a zero reaction's sign bit.
inline Eigen::Matrix<double, 3, 6> contact_rows(const ContactProblem& problem, std::size_t c, int side) {
  assert((side == 0 || !is_wall(problem.body_j[c])) && "contact_rows: side 1 must be a particle");
  const double sign = side == 0 ? 1.0 : -1.0;
  const double lever = side == 0 ? problem.lever_i[c] : problem.lever_j[c];
  const Eigen::Vector3d& n = problem.normal[c];
  Eigen::Matrix3d frame_t;  // rows n, t1, t2
  frame_t.row(0) = n.transpose();
  frame_t.row(1) = problem.tangent1[c].transpose();
  frame_t.row(2) = problem.tangent2[c].transpose();
  if (problem.dimension == 2) frame_t.row(2).setZero();
  Eigen::Matrix3d cross_n;  // N
  cross_n << 0.0, -n[2], n[1], n[2], 0.0, -n[0], -n[1], n[0], 0.0;
  Eigen::Matrix<double, 3, 6> rows;
  rows.leftCols<3>() = sign * frame_t;
  rows.rightCols<3>() = lever * frame_t * cross_n;
  return rows;
}

// Rolling (ContactProblem::rolling): the relative spin omega_i - omega_j of contact c without
// its component along n, rad/s (a wall does not turn).
template <class Vec>
inline Vec rolling_velocity(const ContactProblem& problem, std::size_t c,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  const Vec n(problem.normal[c]);
  const std::int32_t j = problem.body_j[c];
  Vec relative(angular_velocity[problem.body_i[c]]);
  if (!is_wall(j)) relative = relative - Vec(angular_velocity[j]);
  return relative - relative.dot(n) * n;
}

// A rolling angular impulse m (N m s, global) as body i (+m) and a particle j (-m) take it.
template <class Vec>
inline void take_rolling_impulse_as_i(const Vec& m, double inverse_inertia, Eigen::Vector3d& angular_velocity) {
  add_to(angular_velocity, inverse_inertia * m);
}
template <class Vec>
inline void take_rolling_impulse_as_j(const Vec& m, double inverse_inertia, Eigen::Vector3d& angular_velocity) {
  subtract_from(angular_velocity, inverse_inertia * m);
}

// angular_velocity += W m for a rolling impulse m of contact c.
template <class Vec>
inline void apply_rolling_impulse(const ContactProblem& problem, std::size_t c, const Vec& m,
                                  std::vector<Eigen::Vector3d>& angular_velocity) {
  const std::int32_t i = problem.body_i[c], j = problem.body_j[c];
  take_rolling_impulse_as_i(m, problem.inverse_inertia[i], angular_velocity[i]);
  if (!is_wall(j)) take_rolling_impulse_as_j(m, problem.inverse_inertia[j], angular_velocity[j]);
}

}  // namespace tmdem::mechanics
