#pragma once
// Keeps the thermal network's edge set (the sparsity pattern) steady while a moving packing's
// contacts flicker. Contacts that open keep a zero-conductance edge, so the pattern only changes
// when a pair never seen in the current pattern closes; at that moment the pattern is rebuilt
// from the contacts active now, which also drops the stale edges. Between such events the
// implicit integrator keeps its history and its symbolic factorization.
#include <cstdint>
#include <utility>
#include <vector>

#include "coupling/bridge/ContactList.h"

namespace tmdem::coupling {

class ContactPattern {
 public:
  // active: the contacts of this step in canonical (i, j) order. Fills `pattern` with every
  // pair of the pattern (forces of inactive pairs 0) and `is_active` per pattern entry.
  // Returns true when the pattern had to be rebuilt.
  bool update(const ContactList& active, ContactList& pattern, std::vector<std::uint8_t>& is_active);

  std::size_t size() const { return pairs_.size(); }
  // The pattern's pairs, sorted (checkpoints), and putting them back (restart).
  const std::vector<std::pair<std::int64_t, std::int64_t>>& pairs() const { return pairs_; }
  void restore(std::vector<std::pair<std::int64_t, std::int64_t>> pairs) { pairs_ = std::move(pairs); }

 private:
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs_;  // sorted
};

}  // namespace tmdem::coupling
