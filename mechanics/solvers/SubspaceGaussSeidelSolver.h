#pragma once
// Gauss-Seidel with subspace minimisation on the active set ("nlgs_subspace"; the PGS-SM of
// Silcowitz, Niebe and Erleben, GRAPP 2010): the symmetric sweeps of "nlgs" (GaussSeidelSweep.h,
// GaussSeidelUpdate.h), and after each forward-backward pair the subspace step of
// ActiveSetSubspaceStep.h, a sparse direct solve of the contacts the pair left closed.
//
// Why: Gauss-Seidel moves a load one contact per visit, so its contraction per sweep degrades
// with the depth of the force chains (a column of n spheres: about 1 - c / n^2 per sweep; heavy
// on light: rho = sqrt(b / (a + b)) per sweep, ColumnStatics.h). The subspace step solves a
// closed chain at once, whatever its depth and masses. The solve only stops right after a
// Gauss-Seidel sweep, on the stop test of "nlgs" (GaussSeidelStopTest: the same relative change,
// stop_speed cap and stall rule), so it is judged like the others, and its reactions are those
// of a sweep, each inside its cone. Rolling impulses are left to the sweeps.
//
// Measured (cold solves to 1e-6 of lattice piles of 4 x 4 columns, mu = 0.3, one step from rest,
// bench_solvers BM_PileHeight; docs/mechanics.md): the sweeps stay flat from 10 to 160 layers
// (and under a 100x heavier top layer) where "nlgs" and "nncg" grow with the height. On the
// stored steps of the examples, where the sweeps do not find the active set, the steps are
// rejected and it is "nlgs"; "nncg_subspace" (NncgSolver.h) adds the same step to "nncg".
//
// Allocation: the sweeps none once warm; the subspace step's: ActiveSetSubspaceStep.h.

#include <vector>

#include "mechanics/solvers/ActiveSetSubspaceStep.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/GaussSeidelSweep.h"

namespace tmdem::mechanics {

class SubspaceGaussSeidelSolver final : public ContactSolver {
 public:
  explicit SubspaceGaussSeidelSolver(const SolverSettings& settings)
      : SubspaceGaussSeidelSolver(settings, ActiveSetSubspaceStep::Options{}) {}
  SubspaceGaussSeidelSolver(const SolverSettings& settings, const ActiveSetSubspaceStep::Options& options);
  std::string_view name() const override { return "nlgs_subspace"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;

  // The subspace steps of the last solve (tried, kept, factorisations).
  const ActiveSetSubspaceStep& subspace() const { return subspace_; }

 private:
  SolverSettings settings_;
  GaussSeidelSweep sweep_;  // index order, every sweep full
  ActiveSetSubspaceStep subspace_;
};

}  // namespace tmdem::mechanics
