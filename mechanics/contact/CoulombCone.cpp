#include "mechanics/contact/CoulombCone.h"

#include <cmath>

namespace tmdem::mechanics {

Eigen::Vector3d project_onto_coulomb_cone(const Eigen::Vector3d& tau, double mu) {
  const double tn = tau[0];
  const double tt = std::hypot(tau[1], tau[2]);
  if (tn >= 0.0 && tt <= mu * tn) return tau;           // inside the cone: stick
  if (mu * tt <= -tn) return Eigen::Vector3d::Zero();    // polar cone: no contact
  // Slip: nearest point on the cone surface, r_n = (tau_n + mu |tau_t|) / (1 + mu^2),
  // r_t = mu r_n tau_t / |tau_t| (tt > 0 here, else one of the cases above held).
  const double rn = (tn + mu * tt) / (1.0 + mu * mu);
  const double scale = mu * rn / tt;
  return Eigen::Vector3d(rn, scale * tau[1], scale * tau[2]);
}

int solve_contact_bipotential_iterative(const Eigen::Vector3d& u0, double w_n, double w_t,
                                        double mu, Eigen::Vector3d& r,
                                        double relative_tolerance, int max_passes) {
  // Scaling S = diag(sqrt(w_n), sqrt(w_t), sqrt(w_t)): r' = S r, u' = S^-1 u = u0' + r'.
  // The cone S K_mu is K_mu' with mu' = mu sqrt(w_t/w_n), and S^-1 u~ is the modified
  // velocity of (u', mu'); normal cones map by S^-1, so -u~' in N_K'(r') is the same law.
  const double sn = std::sqrt(w_n), st = std::sqrt(w_t);
  const double mu_s = mu * st / sn;
  const Eigen::Vector3d u0s(u0[0] / sn, u0[1] / st, u0[2] / st);
  Eigen::Vector3d rs(r[0] * sn, r[1] * st, r[2] * st);
  int pass = 0;
  while (pass < max_passes) {
    ++pass;
    const Eigen::Vector3d us = u0s + rs;
    const double slip = std::hypot(us[1], us[2]);
    // Predictor with rho = 1 (the block is the identity in these variables).
    const Eigen::Vector3d tau(rs[0] - (us[0] + mu_s * slip), rs[1] - us[1], rs[2] - us[2]);
    const Eigen::Vector3d next = project_onto_coulomb_cone(tau, mu_s);
    const double change = (next - rs).norm();
    rs = next;
    if (change <= relative_tolerance * rs.norm()) break;
  }
  r = Eigen::Vector3d(rs[0] / sn, rs[1] / st, rs[2] / st);
  return pass;
}

}  // namespace tmdem::mechanics
