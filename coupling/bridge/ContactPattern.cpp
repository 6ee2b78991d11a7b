#include "coupling/bridge/ContactPattern.h"

namespace tmdem::coupling {

bool ContactPattern::update(const ContactList& active, ContactList& pattern,
                            std::vector<std::uint8_t>& is_active) {
  // Merge walk: both lists are sorted by (i, j).
  bool contained = true;
  {
    std::size_t p = 0;
    for (std::size_t c = 0; c < active.size() && contained; ++c) {
      const std::pair key(active.pair[2 * c], active.pair[2 * c + 1]);
      while (p < pairs_.size() && pairs_[p] < key) ++p;
      contained = p < pairs_.size() && pairs_[p] == key;
    }
  }
  const bool rebuilt = !contained;
  if (rebuilt) {
    pairs_.clear();
    for (std::size_t c = 0; c < active.size(); ++c)
      pairs_.emplace_back(active.pair[2 * c], active.pair[2 * c + 1]);
  }
  pattern.clear();
  is_active.assign(pairs_.size(), 0);
  std::size_t c = 0;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    double force = 0.0;
    if (c < active.size() && std::pair(active.pair[2 * c], active.pair[2 * c + 1]) == pairs_[p]) {
      force = active.normal_force_N[c++];
      is_active[p] = 1;
    }
    pattern.add(pairs_[p].first, pairs_[p].second, force);
  }
  return rebuilt;
}

}  // namespace tmdem::coupling
