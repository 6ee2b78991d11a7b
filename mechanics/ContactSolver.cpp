#include "mechanics/ContactSolver.h"

#include <stdexcept>
#include <string>

namespace tmdem::mechanics {

SolveReport ContactSolver::solve_with_rolling(const ContactProblem& problem,
                                              std::vector<Eigen::Vector3d>& r,
                                              std::vector<Eigen::Vector3d>& m,
                                              std::vector<Eigen::Vector3d>& velocity,
                                              std::vector<Eigen::Vector3d>& angular_velocity) {
  if (problem.rolling) {
    throw std::invalid_argument("mechanics: solver \"" + std::string(name()) +
                                "\" does not support rolling friction (use \"nlgs\", "
                                "\"nlgs_coloured\" or \"apgd\", or set rolling_friction = 0)");
  }
  m.assign(problem.size(), Eigen::Vector3d::Zero());
  return solve(problem, r, velocity, angular_velocity);
}

}  // namespace tmdem::mechanics
