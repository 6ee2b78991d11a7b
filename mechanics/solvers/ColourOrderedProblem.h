#pragma once
// A contact problem copied into colour order (ContactColouring.h), with its reactions: what a
// Gauss-Seidel solver that sweeps colour by colour, each colour one OpenMP loop, works on
// ("nlgs_coloured", "nncg_coloured"). load() colours the problem (again only when its contact
// list changed) and copies it in; store() puts the solved reactions back in the problem's own
// order. No allocation once warm.
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactColouring.h"
#include "mechanics/solvers/ReorderedProblem.h"

namespace tmdem::mechanics {

class ColourOrderedProblem {
 public:
  // parallel: copy with OpenMP threads (per-index writes: the same bits for any thread count).
  void load(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
            const std::vector<Eigen::Vector3d>& m, bool parallel) {
    colouring_.update(problem);
    ordered_.load(problem, colouring_.order(), r, m, parallel);
  }
  void store(std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m, bool parallel) const {
    ordered_.store(r, m, parallel);
  }

  const ContactProblem& problem() const { return ordered_.problem(); }
  std::vector<Eigen::Vector3d>& r() { return ordered_.r(); }
  std::vector<Eigen::Vector3d>& m() { return ordered_.m(); }
  // Contacts [colour_start()[k], colour_start()[k + 1]) of problem() have colour k.
  const std::vector<std::int32_t>& colour_start() const { return colouring_.start(); }
  const ContactColouring& colouring() const { return colouring_; }

 private:
  ContactColouring colouring_;
  ReorderedProblem ordered_;
};

}  // namespace tmdem::mechanics
