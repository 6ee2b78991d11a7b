#include "mechanics/integrator/PenetrationCorrection.h"

#include <algorithm>
#include <cstddef>

#include "mechanics/solvers/ContactSolverRegistry.h"

namespace tmdem::mechanics {
namespace {

SolverSettings correction_settings(SolverSettings settings) {
  settings.tolerance = std::max(settings.tolerance, PenetrationCorrection::kTolerance);
  return settings;
}

}  // namespace

PenetrationCorrection::PenetrationCorrection(const SolverSettings& settings)
    : solver_(make_contact_solver("nlgs", correction_settings(settings))) {}

SolveReport PenetrationCorrection::correct(const ContactProblem& problem,
                                           const std::vector<double>& gap_m, double slop_m,
                                           double recovery_speed_m_per_s, double h_s,
                                           std::vector<Eigen::Vector3d>& position, bool move_pistons) {
  SolveReport report;
  report.converged = true;
  const double trigger_m = kTrigger * slop_m;
  bool needed = false;
  for (std::size_t c = 0; c < problem.size() && !needed; ++c)
    needed = problem.solvable(c) && gap_m[c] < -trigger_m;
  if (!needed) return report;

  // Copy-assignment keeps the capacity: no allocation once warm.
  problem_ = problem;
  std::fill(problem_.free_velocity.begin(), problem_.free_velocity.end(), Eigen::Vector3d::Zero());
  std::fill(problem_.free_angular_velocity.begin(), problem_.free_angular_velocity.end(),
            Eigen::Vector3d::Zero());
  std::fill(problem_.mu.begin(), problem_.mu.end(), 0.0);
  problem_.rolling = false;  // frictionless, and no rolling resistance: normals only
  problem_.compliant = false;  // positions of rigid contacts (a compliant law keeps its overlaps)
  problem_.stop_speed = 0.0;  // displacements, not impulses: relative to the whole correction
  // Walls stay where they are, pistons too unless move_pistons: then a piston takes its share
  // by its inverse mass, as in the velocity problem.
  if (!move_pistons) {
    for (std::size_t c = 0; c < problem_.size(); ++c) {
      if (is_wall(problem_.body_j[c]))
        problem_.w_n[c] = problem.w_n[c] - problem.inverse_mass[problem.wall_body(problem_.body_j[c])];
    }
    std::fill(problem_.inverse_mass.begin() + std::ptrdiff_t(problem_.particle_count),
              problem_.inverse_mass.end(), 0.0);
  }
  for (std::size_t c = 0; c < problem_.size(); ++c) {
    const double allowed_m = gap_m[c] < -trigger_m ? slop_m : std::max(slop_m, -gap_m[c]);
    double b = (gap_m[c] + allowed_m) / h_s;
    if (recovery_speed_m_per_s > 0.0) b = std::max(b, -recovery_speed_m_per_s);
    problem_.bias[c] = b;
  }
  impulse_.assign(problem_.size(), Eigen::Vector3d::Zero());
  report = solver_->solve(problem_, impulse_, velocity_, angular_velocity_);
  for (std::size_t i = 0; i < position.size(); ++i) {
    if (problem_.inverse_mass[i] > 0.0) position[i] += h_s * velocity_[i];
  }
  return report;
}

}  // namespace tmdem::mechanics
