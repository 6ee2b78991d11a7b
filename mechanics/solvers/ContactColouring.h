#pragma once
// Greedy colouring of the contact graph for a parallel Gauss-Seidel: two contacts that share
// a particle get different colours, so the contacts of one colour touch disjoint bodies and
// can be visited at the same time (a fixed wall is not a body here: any number of contacts of
// one colour may touch it; a piston, whose velocity the contacts change, is one). Deterministic: contacts are coloured in index order, each
// taking the smallest colour that none of its bodies' earlier contacts has (at most
// 2 * (largest contacts per body) - 1 colours).
//
// Recomputed only when the contact list changes (the candidate table was rebuilt); checking
// costs one comparison of the body lists, far less than one sweep.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

class ContactColouring {
 public:
  // Colours problem's contacts unless they are the ones coloured last time. Returns true
  // when it coloured afresh.
  bool update(const ContactProblem& problem);

  std::size_t colour_count() const { return start_.empty() ? 0 : start_.size() - 1; }
  // Contacts of colour k: order()[start()[k], start()[k + 1]), in increasing index order.
  const std::vector<std::int32_t>& order() const { return order_; }
  const std::vector<std::int32_t>& start() const { return start_; }
  std::size_t recolourings() const { return recolourings_; }

 private:
  bool colour(const ContactProblem& problem, std::size_t words);

  std::vector<std::int32_t> body_i_, body_j_;  // the contact list last coloured
  std::vector<std::int32_t> colour_, order_, start_, cursor_;
  std::vector<std::uint64_t> used_;  // per body: colours taken by its contacts (bit set)
  std::size_t recolourings_ = 0;
};

}  // namespace tmdem::mechanics
