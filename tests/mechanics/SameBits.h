#pragma once
// Bit-for-bit equality: the restart, thread-count and rewrite tests ask for the same bits, not
// closeness.
#include <cstring>
#include <vector>

namespace tmdem::mechanics::test {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace tmdem::mechanics::test
