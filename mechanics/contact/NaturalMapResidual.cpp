#include "mechanics/contact/NaturalMapResidual.h"

#include "mechanics/contact/BlockedSum.h"
#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  const SumPair sums = blocked_sum<SumPair>(problem.size(), [&](std::size_t c, SumPair& sum) {
    // An open candidate that stays open adds nothing (up to the round-off of the spins' lever
    // terms in the full local velocity, which are perpendicular to n).
    if (!problem.solvable(c) || stays_open(problem, c, r[c], velocity)) return;
    const Eigen::Vector3d next =
        local_law_solution(problem, c, r[c], local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity));
    sum.first += (next - r[c]).norm();  // the defect
    sum.second += next.norm();          // the total
  });
  return natural_map_ratio(sums.first, sums.second);
}

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& m,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  if (!problem.rolling) return natural_map_residual(problem, r, velocity, angular_velocity);
  const SumPair sums = blocked_sum<SumPair>(problem.size(), [&](std::size_t c, SumPair& sum) {
    if (!problem.solvable(c) || (m[c].isZero(0.0) && stays_open(problem, c, r[c], velocity))) return;
    const Eigen::Vector3d next =
        local_law_solution(problem, c, r[c], local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity));
    const Eigen::Vector3d next_m = local_rolling_solution(
        problem, c, next[0], m[c], rolling_velocity<Eigen::Vector3d>(problem, c, angular_velocity));
    const double scale = 1.0 / problem.rolling_radius[c];
    sum.first += (next - r[c]).norm() + (next_m - m[c]).norm() * scale;
    sum.second += next.norm() + next_m.norm() * scale;
  });
  return natural_map_ratio(sums.first, sums.second);
}

}  // namespace tmdem::mechanics
