#pragma once
// A contact problem solved in a spatial order (issue 10): the solver is handed a copy of the
// problem whose particles are numbered along a Morton (Z-order) curve of their cells and
// whose contacts are sorted by those numbers, and the reactions and velocities are mapped
// back to the problem's own numbering afterwards. Nothing outside the solve sees the order:
// particle ids, the candidate table, the contact list and the result file keep theirs.
//
// Why: a Gauss-Seidel visit reads and writes the velocities of its two bodies. Particles
// placed at random (RandomPlacement.h) are numbered at random in space, so consecutive
// contacts touch bodies far apart in the per-body arrays; once those arrays outgrow the
// cache every visit waits for memory. Measured (one thread, "nlgs", 100 sweeps with rolling
// resistance, `bench_solvers --benchmark_filter=BM_SweepsOrder`, two runs at load 5 and 10):
// the lattice pile costs 32-34 ns per contact per sweep as built (neighbours have near
// numbers) at 2,000 to 100,000 spheres; numbered at random, 36-37 ns at 2,000, 40-44 at
// 10,000, 43-50 at 20,000, 58-74 at 100,000; numbered at random and solved through this
// class, 35, 36-37, 36-39 and 39-42. A poured bed is less sensitive (its open candidates only
// read two velocities): the settled 2,000 bed tiled into larger beds with ids at random gains
// nothing at 18,000 spheres and 13% at 98,000 (figures at NscdParameters::spatial_order_from,
// from which NscdIntegrator uses this class).
//
// Cost: one copy of the problem per solve (O(contacts + bodies), parallel like the contact
// set-up) and its memory (about 200 bytes per candidate); the order itself is computed again
// only when the candidate table changes (update()).
//
// Determinism: the order depends only on the positions and pairs given to update(); the
// copies write one slot each. The same inputs give the same bits for a given thread count
// (the solver's own rule); the visiting order differs from the problem's, so the iterates
// differ from an unordered solve by round-off (the fixed point is the same).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "mechanics/model/ParallelFrom.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::mechanics {

class SpatialContactOrder {
 public:
  // Copy loops use OpenMP threads from this many contacts on (NscdParameters::parallel_from).
  explicit SpatialContactOrder(std::ptrdiff_t parallel_from = kDefaultParallelFrom) : parallel_from_(parallel_from) {}

  // The candidate table changed: the next solve needs update() first.
  void invalidate() { valid_ = false; }
  bool valid() const { return valid_; }

  // Computes the order of `problem` (its pairs; per-step values are not read) from particle
  // positions `position_m` (one per particle of the problem): particles by the Morton code of
  // their cell of edge cell_m (ties by id), contacts by (smaller, larger) new body number of
  // their two bodies, wall contacts by (particle, wall) before the particle pairs of that
  // particle. Throws std::invalid_argument if the sizes do not fit or cell_m is not positive.
  void update(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& position_m,
              double cell_m);

  // solver.solve_with_rolling on the reordered copy of `problem` (which must have the pairs
  // given to the last update()), with r, m, velocity and angular_velocity in problem's own
  // numbering, as ContactSolver::solve_with_rolling takes them (m is not read without rolling).
  SolveReport solve(ContactSolver& solver, const ContactProblem& problem,
                    std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m,
                    std::vector<Eigen::Vector3d>& velocity,
                    std::vector<Eigen::Vector3d>& angular_velocity);

  // The order: the new number of particle p, and the contact of the problem at each position
  // of the reordered copy; and the copy the last solve() handed the solver.
  const std::vector<std::int32_t>& body_number() const { return number_; }
  const std::vector<std::int32_t>& contact_order() const { return order_; }
  const ContactProblem& ordered_problem() const { return ordered_; }

 private:
  void gather(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
              const std::vector<Eigen::Vector3d>& m);

  std::ptrdiff_t parallel_from_;
  bool valid_ = false;
  std::vector<std::int32_t> number_;  // new body number of each particle
  std::vector<std::int32_t> order_;   // problem contact at each position of ordered_
  std::vector<std::pair<std::uint64_t, std::int32_t>> keys_;  // sort scratch
  ContactProblem ordered_;
  std::vector<Eigen::Vector3d> r_, m_, velocity_, angular_velocity_;
};

}  // namespace tmdem::mechanics
