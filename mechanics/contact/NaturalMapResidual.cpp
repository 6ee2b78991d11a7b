#include "mechanics/contact/NaturalMapResidual.h"

#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  double defect = 0.0, total = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    // An open candidate that stays open adds nothing (up to the round-off of the spins' lever
    // terms in the full local velocity, which are perpendicular to n).
    if (!problem.solvable(c) || stays_open(problem, c, r[c], velocity)) continue;
    const Eigen::Vector3d next =
        local_law_solution(problem, c, r[c], local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity));
    defect += (next - r[c]).norm();
    total += next.norm();
  }
  return natural_map_ratio(defect, total);
}

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& m,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  if (!problem.rolling) return natural_map_residual(problem, r, velocity, angular_velocity);
  double defect = 0.0, total = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (!problem.solvable(c) || (m[c].isZero(0.0) && stays_open(problem, c, r[c], velocity))) continue;
    const Eigen::Vector3d next =
        local_law_solution(problem, c, r[c], local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity));
    const Eigen::Vector3d next_m = local_rolling_solution(
        problem, c, next[0], m[c], rolling_velocity<Eigen::Vector3d>(problem, c, angular_velocity));
    const double scale = 1.0 / problem.rolling_radius[c];
    defect += (next - r[c]).norm() + (next_m - m[c]).norm() * scale;
    total += next.norm() + next_m.norm() * scale;
  }
  return natural_map_ratio(defect, total);
}

}  // namespace tmdem::mechanics
