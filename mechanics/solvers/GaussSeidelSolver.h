#pragma once
// Nonlinear Gauss-Seidel ("equilibres successifs", [JEA 99]) over the contacts: each contact
// solves its own bipotential law with the others frozen (closed form, CoulombCone.h) and
// updates the two bodies' velocities at once. Registered as "nlgs". Most sweeps visit the
// active contacts only, a full sweep every SolverSettings::full_sweep_every sweeps and before
// convergence is declared (ActiveContactSet.h).

#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/GaussSeidelSweep.h"

namespace tmdem::mechanics {

class GaussSeidelSolver final : public ContactSolver {
 public:
  explicit GaussSeidelSolver(const SolverSettings& settings);
  std::string_view name() const override { return "nlgs"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;

 private:
  SolverSettings settings_;
  GaussSeidelSweep sweep_;  // index order, active set after SolverSettings::full_sweep_every
};

}  // namespace tmdem::mechanics
