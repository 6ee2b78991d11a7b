#pragma once
// A contact problem copied into colour order (ContactColouring.h), with its reactions: what a
// Gauss-Seidel solver that sweeps colour by colour, each colour one OpenMP loop, works on
// ("nlgs_coloured", "nncg_coloured"). load() copies the problem and the warm start in, store()
// puts the solved reactions back in the problem's own order. No allocation once warm.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactColouring.h"

namespace tmdem::mechanics {

class ColourOrderedProblem {
 public:
  // parallel: copy with OpenMP threads (per-index writes: the same bits for any thread count).
  void load(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
            const std::vector<Eigen::Vector3d>& m, bool parallel);
  void store(std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m, bool parallel) const;

  const ContactProblem& problem() const { return ordered_; }
  std::vector<Eigen::Vector3d>& r() { return ordered_r_; }
  std::vector<Eigen::Vector3d>& m() { return ordered_m_; }
  // Contacts [colour_start()[k], colour_start()[k + 1]) of problem() have colour k.
  const std::vector<std::int32_t>& colour_start() const { return colouring_.start(); }
  const ContactColouring& colouring() const { return colouring_; }

 private:
  ContactColouring colouring_;
  ContactProblem ordered_;                  // contact p is contact colouring_.order()[p]
  std::vector<Eigen::Vector3d> ordered_r_;  // reactions in colour order
  std::vector<Eigen::Vector3d> ordered_m_;  // rolling impulses in colour order
};

}  // namespace tmdem::mechanics
