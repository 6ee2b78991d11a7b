#pragma once
// The Coulomb cone and the rolling cone of one contact together (ContactProblem.h): the
// reactions (r_n, r_t, m) of a contact with rolling resistance lie in
//   K = { |r_t| <= mu r_n,  |m| <= mu_r r_n }      (mu_r here: the lever mu_r R_eff, in m)
// two cones sharing the normal axis. A Jacobi-type solver (ApgdSolver.h) moves all three
// parts of a contact at once and needs the Euclidean projection onto K, which couples them
// through r_n; Gauss-Seidel solves the blocks one after the other and never needs it.

namespace tmdem::mechanics {

// The projection of a point (normal, t, s) onto K, with tangential = |t| and rolling = |s|
// (vectors in their own planes, whatever their dimension): the nearest point is
// (r_n, tangential_factor t, rolling_factor s), factors in [0, 1].
//
// For a given r_n the nearest t and s are t and s cut to radius mu r_n and mu_r r_n, so r_n
// minimises the convex piecewise quadratic
//   (r_n - normal)^2 + (|t| - mu r_n)_+^2 + (|s| - mu_r r_n)_+^2   over r_n >= 0,
// whose derivative is piecewise linear and increasing with kinks at |t| / mu and |s| / mu_r:
// the root is found exactly on the first interval that holds it. A zero coefficient pins its
// part to 0 (mu = 0: frictionless; mu_r = 0: no rolling resistance) and leaves r_n free of it.
struct TwoConeProjection {
  double normal = 0.0;
  double tangential_factor = 0.0;
  double rolling_factor = 0.0;
};
TwoConeProjection project_onto_coulomb_and_rolling_cones(double normal, double tangential,
                                                         double mu, double rolling, double mu_r);

}  // namespace tmdem::mechanics
