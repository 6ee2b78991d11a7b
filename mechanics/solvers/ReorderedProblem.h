#pragma once
// A contact problem with its contacts copied into another order, with their reactions: what a
// solver that sweeps in an order of its own works on with contiguous memory (colour order,
// ColourOrderedProblem.h; slab order, ContactSlabs.h). load() copies the problem and the warm
// start in, store() puts the solved reactions back in the problem's own order. No allocation
// once warm.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

class ReorderedProblem {
 public:
  // Slot p gets contact order[p] of problem (order: a permutation of its contacts). parallel:
  // copy with OpenMP threads (per-slot writes: the same bits for any thread count).
  void load(const ContactProblem& problem, const std::vector<std::int32_t>& order,
            const std::vector<Eigen::Vector3d>& r, const std::vector<Eigen::Vector3d>& m,
            bool parallel);
  void store(std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m, bool parallel) const;

  const ContactProblem& problem() const { return ordered_; }
  std::vector<Eigen::Vector3d>& r() { return ordered_r_; }
  std::vector<Eigen::Vector3d>& m() { return ordered_m_; }

 private:
  std::vector<std::int32_t> order_;         // the order of the last load()
  ContactProblem ordered_;                  // contact p is contact order_[p]
  std::vector<Eigen::Vector3d> ordered_r_;  // reactions in that order
  std::vector<Eigen::Vector3d> ordered_m_;  // rolling impulses in that order
};

}  // namespace tmdem::mechanics
