#pragma once
// The bipotential contact law of De Saxce & Feng [SAX 98] for one frictional contact.
//
// Local coordinates: component 0 is along the normal n (from body j to body i), components
// 1 and 2 along two tangents. u is the relative velocity of i with respect to j at the
// contact point (m/s), r the reaction impulse of j on i (N s).
//
// The law: r lies in the Coulomb cone K_mu = { |r_t| <= mu r_n }, and the "modified
// velocity" u~ = u_t + (u_n + mu |u_t|) n satisfies -u~ in N_K(r). Written as a fixed point
// for any rho > 0: r = proj_K( r - rho u~ ), which gives the predictor-corrector
//   predictor  tau = r - rho (u_t + (u_n + mu |u_t|) n)
//   corrector  r   = proj(tau, K_mu)   (stick, slip or no contact)
// This single relation covers unilateral contact and Coulomb friction together.

#include <Eigen/Core>
#include <cmath>

#include "mechanics/contact/BranchFreeMin.h"

namespace tmdem::mechanics {

// Euclidean projection of tau (local coordinates) onto K_mu:
//   tau in K_mu                         -> tau               (stick)
//   tau in the polar cone mu|t| <= -n   -> 0                 (no contact)
//   otherwise                           -> nearest point of the cone surface (slip)
Eigen::Vector3d project_onto_coulomb_cone(const Eigen::Vector3d& tau, double mu);

// One contact with every other reaction frozen: u = u0 + W r with the Delassus block
// W = diag(w_n, w_t, w_t) (diagonal for spheres: the contact point lies on the line of
// centres, so normal and tangential impulses do not couple). u0[0] already holds the
// position (gap) term of the Signorini condition.
//
// The bipotential fixed point r = proj_K(r - rho u~) has a closed form for this block. In the
// scaled variables r' = W^(1/2) r, u' = W^(-1/2) u the block is the identity, the law keeps
// its form with mu' = mu sqrt(w_t / w_n), and with rho = 1 (the natural step, rho_n = 1/w_n,
// rho_t = 1/w_t in the original variables) the predictor is tau = -u0' - mu' |u'_t| n: its
// tangential part does not depend on r. The three statuses then read directly:
//   u0_n >= 0                      -> r = 0                     (no contact)
//   |u0_t| / w_t <= mu (-u0_n/w_n) -> r = -W^-1 u0              (stick: u = 0)
//   otherwise                      -> r_n = -u0_n / w_n, r_t = -mu r_n u0_t / |u0_t|
//                                                               (slip: u_n = 0, u_t || u0_t)
// i.e. the predictor-corrector converged (its passes contract slip by mu'^2 / (1 + mu'^2)
// each, so 10 to 50 of them were needed before). The result is exact to round-off; r's input
// value (a warm start for the iterative form) is ignored. Returns the number of passes, 1.
// Inline: every Gauss-Seidel visit calls it (GaussSeidelUpdate.h).
inline int solve_contact_bipotential(const Eigen::Vector3d& u0, double w_n, double w_t, double mu,
                                     Eigen::Vector3d& r) {
  if (!(u0[0] < 0.0)) {  // separating or grazing: no contact
    r.setZero();
    return 1;
  }
  const double rn = -u0[0] / w_n;  // u_n = 0 while in contact
  const double rt1 = -u0[1] / w_t, rt2 = -u0[2] / w_t;
  // Not std::hypot: its overflow-safe scaling cost 15% of a visit on the pour bed (79 against
  // 94 ns per candidate per sweep, measured in development), and impulses are nowhere near
  // overflow.
  const double rt = std::sqrt(rt1 * rt1 + rt2 * rt2);
  // Stick (|r_t| <= mu r_n: u = 0) keeps r_t; slip puts r on the cone surface, opposite to
  // the tangential velocity (which keeps the direction of u0_t since W is a multiple of the
  // identity on the tangent plane): r_t scaled by mu r_n / |r_t|. One formula without a
  // branch (BranchFreeMin.h: stick and slip alternate unpredictably on a poured bed), r_t
  // scaled by min(1, mu r_n / |r_t|): a correctly rounded quotient a / b is below 1 exactly
  // when a < b, so slip gets the scale it always had and stick 1 (the same bits); rt = 0
  // gives inf or NaN, and min(1, NaN) is 1.
  const double scale = branch_free_min(1.0, mu * rn / rt);
  r = Eigen::Vector3d(rn, scale * rt1, scale * rt2);
  return 1;
}

// The predictor-corrector itself (rho = 1 in the scaled variables above), from r as a warm
// start, until the change is below relative_tolerance or after max_passes; returns the
// number of passes. Kept as the reference the closed form is checked against.
int solve_contact_bipotential_iterative(const Eigen::Vector3d& u0, double w_n, double w_t,
                                        double mu, Eigen::Vector3d& r,
                                        double relative_tolerance, int max_passes);

}  // namespace tmdem::mechanics
