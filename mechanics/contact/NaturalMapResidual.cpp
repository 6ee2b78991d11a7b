#include "mechanics/contact/NaturalMapResidual.h"

#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

namespace {

// An open candidate that stays open (r_c = 0, u_n >= 0): its local solution is 0 (and so its
// rolling one), so it adds nothing to either sum (up to the round-off of the spins' lever terms
// in the full local velocity, which are perpendicular to n). Most candidates of a look-ahead
// detection are such; the test reads the normal velocity alone (GaussSeidelUpdate.h skips them
// the same way).
bool open_and_opening(const ContactProblem& problem, std::size_t c, const Eigen::Vector3d& r_c,
                      const std::vector<Eigen::Vector3d>& velocity) {
  return r_c[0] == 0.0 && r_c[1] == 0.0 && r_c[2] == 0.0 && !(normal_velocity(problem, c, velocity) < 0.0);
}

}  // namespace

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  double defect = 0.0, total = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (!problem.solvable(c) || open_and_opening(problem, c, r[c], velocity)) continue;
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
    if (!problem.solvable(c) || (m[c].isZero(0.0) && open_and_opening(problem, c, r[c], velocity))) continue;
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
