#pragma once
// Nonlinear Gauss-Seidel ("equilibres successifs", [JEA 99]) over the contacts: each contact
// solves its own bipotential law with the others frozen (closed form, CoulombCone.h) and
// updates the two bodies' velocities at once. Registered as "nlgs". Most sweeps visit the
// active contacts only, a full sweep every SolverSettings::full_sweep_every sweeps and before
// convergence is declared (ActiveContactSet.h). With every sweep full (the default), from
// SolverSettings::parallel_from contacts the sweeps go slab by slab (ContactSlabs.h), OpenMP
// threads sharing each phase's slabs, where the problem gives positions: the same bits for any
// thread count.
// The penetration correction (PenetrationCorrection.h) is solved by this solver.

#include <cstddef>

#include "mechanics/solvers/ContactSlabs.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/GaussSeidelSweep.h"
#include "mechanics/solvers/ReorderedProblem.h"

namespace tmdem::mechanics {

class GaussSeidelSolver final : public ContactSolver {
 public:
  explicit GaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}
  std::string_view name() const override { return "nlgs"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;
  // Whether the last solve swept slabs.
  bool sliced() const { return sliced_; }

 private:
  SolverSettings settings_;
  GaussSeidelSweep sweep_;  // index order, active set after SolverSettings::full_sweep_every
  ContactSlabs slabs_;       // the cut of a large problem
  ReorderedProblem ordered_; // the problem in slab order
  bool sliced_ = false;
};

}  // namespace tmdem::mechanics
