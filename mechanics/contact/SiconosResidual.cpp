#include "mechanics/contact/SiconosResidual.h"

#include <cfloat>
#include <cmath>

#include "mechanics/contact/BlockedSum.h"
#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"

namespace tmdem::mechanics {

double free_velocity_norm(const ContactProblem& problem) {
  return std::sqrt(blocked_sum<double>(problem.size(), [&](std::size_t c, double& sum) {
    if (!problem.solvable(c)) return;
    sum += local_velocity<Eigen::Vector3d>(problem, c, problem.free_velocity, problem.free_angular_velocity)
               .squaredNorm();
  }));
}

double siconos_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                        const std::vector<Eigen::Vector3d>& m,
                        const std::vector<Eigen::Vector3d>& velocity,
                        const std::vector<Eigen::Vector3d>& angular_velocity, double q_norm) {
  const double squared = blocked_sum<double>(problem.size(), [&](std::size_t c, double& sum) {
    if (!problem.solvable(c)) return;
    Eigen::Vector3d u = local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity);
    if (problem.compliant) u[0] += problem.compliance[c] * r[c][0];  // (W r + q)_n of W + C
    const double slip = std::hypot(u[1], u[2]);
    const Eigen::Vector3d tau(r[c][0] - (u[0] + problem.mu[c] * slip), r[c][1] - u[1], r[c][2] - u[2]);
    Eigen::Vector3d defect = r[c] - project_onto_coulomb_cone(tau, problem.mu[c]);
    if (problem.dimension == 2) defect[2] = 0.0;
    sum += defect.squaredNorm();
    if (problem.rolling && problem.w_r[c] > 0.0) {
      // In impulse (N s) and velocity (m/s) units: m / R_eff and spin R_eff.
      const double radius = problem.rolling_radius[c];
      const Eigen::Vector3d spin = rolling_velocity<Eigen::Vector3d>(problem, c, angular_velocity);
      const Eigen::Vector3d mc = m[c] / radius;
      Eigen::Vector3d y = mc - spin * radius;
      const double limit = problem.rolling_limit[c] / radius * std::max(r[c][0], 0.0);
      const double size = y.norm();
      if (size > limit) y *= (size > 0.0 ? limit / size : 0.0);
      sum += (mc - y).squaredNorm();
    }
  });
  const double e = std::sqrt(squared);
  return q_norm > DBL_EPSILON ? e / q_norm : e;
}

}  // namespace tmdem::mechanics
