#pragma once
// Graph-coloured nonlinear Gauss-Seidel, registered as "nlgs_coloured": the local solve of
// "nlgs" (GaussSeidelUpdate.h), visiting the contacts colour by colour (ContactColouring.h).
// The contacts of one colour share no particle, so each colour is one OpenMP loop; a sweep is
// a Gauss-Seidel sweep in the order "colour 0, colour 1, ...", symmetric like "nlgs" (odd
// sweeps go through the colours forwards, even sweeps backwards).
//
// Determinism: within a colour no contact reads what another writes, so the visit order and
// the thread count inside a colour do not matter; the sweep's sums (stop test) add fixed
// blocks of contacts, then the blocks in order. Results are bitwise identical for any thread
// count. They differ from "nlgs" (another visiting order) by less than the tolerance.
//
// Memory: the contacts of a colour are spread over the whole table, so visiting them in
// place touches a dozen arrays at scattered indices. Each solve therefore copies the problem
// into colour order first (one pass, about the cost of one sweep) and sweeps that copy in
// streams; the reactions are copied back at the end.
//
// Active sets: as "nlgs", most sweeps visit the active contacts of each colour only
// (ActiveContactSet.h); the active lists are collected in colour order, so they and the sums
// over them do not depend on the thread count either.
//
// Cost: one barrier per colour per sweep (about 10-30 colours for sphere packings), which
// is why small problems stay on one thread (SolverSettings::parallel_from).

#include <cstddef>
#include <vector>

#include "mechanics/solvers/ColourOrderedProblem.h"
#include "mechanics/solvers/ContactColouring.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/GaussSeidelSweep.h"

namespace tmdem::mechanics {

class ColouredGaussSeidelSolver final : public ContactSolver {
 public:
  explicit ColouredGaussSeidelSolver(const SolverSettings& settings) : settings_(settings) {}
  std::string_view name() const override { return "nlgs_coloured"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m,
                                 std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override;
  const ContactColouring& colouring() const { return ordered_.colouring(); }

 private:
  SolverSettings settings_;
  ColourOrderedProblem ordered_;           // the problem with its contacts in colour order
  GaussSeidelSweep sweep_;                 // colour order, active set per colour
};

}  // namespace tmdem::mechanics
