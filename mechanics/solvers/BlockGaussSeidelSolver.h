#pragma once
// Gauss-Seidel with a block visit per light body ("nlgs_block"): the symmetric sweeps of
// "nlgs" (GaussSeidelSolver.h), except that the contacts of a body at least
// block_mass_ratio times lighter than one of its neighbours are solved together
// (BodyContactBlock.h) in place of their single visits. That removes the slow mode of a light
// sphere carrying a heavy one (contraction b / (a + b) per forward sweep, a = 1/m_heavy,
// b = 1/m_light). Same fixed points as "nlgs" (the law at every contact); the rolling block
// of each contact stays a single visit, after its (n, t) block. Serial and deterministic.

#include <cstdint>
#include <vector>

#include "mechanics/solvers/BodyContactBlock.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/GaussSeidelSweep.h"

namespace tmdem::mechanics {

class BlockGaussSeidelSolver final : public ContactSolver {
 public:
  // Bodies lighter than their heaviest neighbour by at least this factor get a block visit.
  static constexpr double kDefaultMassRatio = 2.0;

  explicit BlockGaussSeidelSolver(const SolverSettings& settings, double mass_ratio = kDefaultMassRatio);
  std::string_view name() const override { return "nlgs_block"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;

  // Of the last solve: bodies with a block visit, block visits, and visits that fell back to
  // single visits (the block's statuses did not settle, or too many closed contacts).
  std::size_t block_count() const { return block_body_.size(); }
  std::int64_t block_visits() const { return block_visits_; }
  std::int64_t block_fallbacks() const { return block_fallbacks_; }

 private:
  struct SweepHooks;  // the block visits of the sweeps (BlockGaussSeidelSolver.cpp)
  void build_blocks(const ContactProblem& problem);

  SolverSettings settings_;
  double mass_ratio_;
  BodyContactBlock block_;
  GaussSeidelSweep sweep_;                   // body_block order, every sweep full
  std::vector<double> heaviest_;             // kg, heaviest mobile neighbour per body
  std::vector<std::int32_t> owner_;          // per contact: its block, -1 for a single visit
  std::vector<std::int32_t> block_body_;     // per block: its body
  std::vector<std::int32_t> block_start_;    // per block: first of its contacts in block_contacts_
  std::vector<std::int32_t> block_contacts_; // contacts grouped by block, in index order
  std::vector<std::int32_t> scratch_;        // block per body, then fill positions
  std::vector<char> quiet_;                  // per block: single visits until they move it
  std::int64_t block_visits_ = 0, block_fallbacks_ = 0;
};

}  // namespace tmdem::mechanics
