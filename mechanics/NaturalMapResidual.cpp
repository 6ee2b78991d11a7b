#include "mechanics/NaturalMapResidual.h"

namespace tmdem::mechanics {

double natural_map_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                            const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity) {
  double defect = 0.0, total = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (!problem.solvable(c)) continue;
    const Eigen::Vector3d next =
        local_law_solution(problem, c, r[c], problem.local_velocity(c, velocity, angular_velocity));
    defect += (next - r[c]).norm();
    total += next.norm();
  }
  return natural_map_ratio(defect, total);
}

}  // namespace tmdem::mechanics
