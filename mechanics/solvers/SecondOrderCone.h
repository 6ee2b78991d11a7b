#pragma once
// The algebra of one second-order cone Q = {x : x_0 >= |x_1..|} of dimension 1 to 3 (dimension
// 1: the half-line x_0 >= 0), as a primal-dual interior-point method needs it (Vandenberghe,
// "The CVXOPT linear and quadratic cone program solvers", 2010, sections 2-4):
//   the Jordan product  x o y = (x . y, x_0 y_1 + y_0 x_1), its identity e = (1, 0, 0),
//   its inverse         lambda \ a (the x with lambda o x = a),
//   the Nesterov-Todd scaling W of an interior pair (s, z): W symmetric positive definite with
//   W s = W^-1 z = lambda, so that W^2 s = z (dimension 1: W = sqrt(z / s)),
//   and the largest step alpha with x + alpha d still in Q.
// Vectors are Eigen::Vector3d whatever the dimension; entries past it are zero and unread.
// Why here and not a library: SUNDIALS and SuiteSparse have no conic solver, and the contact
// problem's cones are all of dimension <= 3, where closed forms beat any general code.

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace tmdem::mechanics::cone {

// x_0^2 - |x_1..|^2 (dimension 1: x_0^2).
inline double hyperbolic_square(int dim, const Eigen::Vector3d& x) {
  double tail = 0.0;
  for (int k = 1; k < dim; ++k) tail += x[k] * x[k];
  return x[0] * x[0] - tail;
}

// The smaller eigenvalue x_0 - |x_1..| (x is interior when it is > 0).
inline double smallest_eigenvalue(int dim, const Eigen::Vector3d& x) {
  double tail = 0.0;
  for (int k = 1; k < dim; ++k) tail += x[k] * x[k];
  return x[0] - std::sqrt(tail);
}

inline Eigen::Vector3d jordan_product(int dim, const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  out[0] = x[0] * y[0];
  for (int k = 1; k < dim; ++k) {
    out[0] += x[k] * y[k];
    out[k] = x[0] * y[k] + y[0] * x[k];
  }
  return out;
}

// The x with lambda o x = a, lambda interior.
inline Eigen::Vector3d jordan_divide(int dim, const Eigen::Vector3d& lambda, const Eigen::Vector3d& a) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (dim == 1) {
    x[0] = a[0] / lambda[0];
    return x;
  }
  double dot = 0.0;
  for (int k = 1; k < dim; ++k) dot += lambda[k] * a[k];
  x[0] = (lambda[0] * a[0] - dot) / hyperbolic_square(dim, lambda);
  for (int k = 1; k < dim; ++k) x[k] = (a[k] - x[0] * lambda[k]) / lambda[0];
  return x;
}

struct Scaling {
  Eigen::Matrix3d w = Eigen::Matrix3d::Zero();          // W (leading dim x dim block)
  Eigen::Matrix3d w_inverse = Eigen::Matrix3d::Zero();  // W^-1
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();     // W s
};

// Nesterov-Todd scaling of interior s, z: eta = (J(z) / J(s))^(1/4), s_ = s / sqrt(J(s)),
// z_ = z / sqrt(J(z)), gamma = sqrt((1 + s_ . z_) / 2), w_ = (z_ + J s_) / (2 gamma) (J w_ = 1),
// W = eta [w_0, w_1^T; w_1, I + w_1 w_1^T / (1 + w_0)], W^-1 = J W J / eta^2.
inline Scaling nesterov_todd(int dim, const Eigen::Vector3d& s, const Eigen::Vector3d& z) {
  Scaling out;
  if (dim == 1) {
    const double w = std::sqrt(z[0] / s[0]);
    out.w(0, 0) = w;
    out.w_inverse(0, 0) = 1.0 / w;
    out.lambda[0] = std::sqrt(s[0] * z[0]);
    return out;
  }
  const double js = std::sqrt(hyperbolic_square(dim, s)), jz = std::sqrt(hyperbolic_square(dim, z));
  const double eta = std::sqrt(jz / js);
  Eigen::Vector3d sb = s / js, zb = z / jz;
  double sz = 0.0;
  for (int k = 0; k < dim; ++k) sz += sb[k] * zb[k];
  const double gamma = std::sqrt(0.5 * (1.0 + sz));
  Eigen::Vector3d wb = Eigen::Vector3d::Zero();
  wb[0] = (zb[0] + sb[0]) / (2.0 * gamma);
  for (int k = 1; k < dim; ++k) wb[k] = (zb[k] - sb[k]) / (2.0 * gamma);
  for (int a = 0; a < dim; ++a)
    for (int b = 0; b < dim; ++b) {
      double entry;
      if (a == 0) entry = wb[b];
      else if (b == 0) entry = wb[a];
      else entry = (a == b ? 1.0 : 0.0) + wb[a] * wb[b] / (1.0 + wb[0]);
      out.w(a, b) = eta * entry;
      const double sign = (a == 0) == (b == 0) ? 1.0 : -1.0;  // J W_ J
      out.w_inverse(a, b) = sign * entry / eta;
    }
  out.lambda = out.w * s;
  return out;
}

// The largest alpha >= 0 with x + alpha d in Q (x interior); infinity when every alpha is.
inline double step_to_boundary(int dim, const Eigen::Vector3d& x, const Eigen::Vector3d& d) {
  constexpr double unbounded = std::numeric_limits<double>::infinity();
  if (dim == 1) return d[0] < 0.0 ? -x[0] / d[0] : unbounded;
  // J(x + alpha d) = a alpha^2 + b alpha + c, c > 0: its smallest positive root (the path
  // leaves Q where J first vanishes), and x_0 + alpha d_0 = 0: a path through the apex has a
  // double root there, which round-off can lose (J then seems to stay positive as the path goes
  // on into -Q).
  double best = d[0] < 0.0 ? -x[0] / d[0] : unbounded;
  const double a = hyperbolic_square(dim, d), c = hyperbolic_square(dim, x);
  double b = x[0] * d[0];
  for (int k = 1; k < dim; ++k) b -= x[k] * d[k];
  b *= 2.0;
  if (a == 0.0) return b < 0.0 ? std::min(best, -c / b) : best;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return best;  // a > 0 then: J stays positive
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  for (double root : {q / a, q != 0.0 ? c / q : unbounded})
    if (root > 0.0 && root < best) best = root;
  return best;
}

}  // namespace tmdem::mechanics::cone
