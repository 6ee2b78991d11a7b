#pragma once
// A sum over the contacts of a problem that threads may share and that gives the same bits for
// any thread count: the contacts are cut into blocks of a fixed size (never by the thread
// count), each block summed in index order by one thread, and the blocks' sums added in block
// order. A problem of one block (below kBlockedSumBlock contacts) is summed as a plain loop, to
// the bit.
//
// Why: the residuals a step measures (Siconos', the natural map's, |q|) are passes over every
// candidate, three a step outside the solve and more inside it. On a 20,000-sphere pour (200,000
// candidates and more) they were the step's serial remainder, about 6% of its wall time on 2
// threads (wide_pour: 18 s of 312 s).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace tmdem::mechanics {

inline constexpr std::size_t kBlockedSumBlock = 4096;

// Two sums carried at once (the natural map's defect and total).
struct SumPair {
  double first = 0.0, second = 0.0;
  SumPair& operator+=(const SumPair& other) {
    first += other.first;
    second += other.second;
    return *this;
  }
};

// The sum over c in [0, count) of term(c, sum), where term adds contact c's share to its second
// argument (a T: double, or SumPair for two sums at once), T{} its zero.
template <class T, class Term>
T blocked_sum(std::size_t count, Term&& term) {
  const std::size_t blocks = (count + kBlockedSumBlock - 1) / kBlockedSumBlock;
  if (blocks <= 1) {
    T sum{};
    for (std::size_t c = 0; c < count; ++c) term(c, sum);
    return sum;
  }
  // Grows to the largest problem seen, then no allocation (the step loop's rule).
  thread_local std::vector<T> partial;
  partial.assign(blocks, T{});
  T* const slots = partial.data();  // the caller's vector: each thread would name its own
  const auto block_count = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t b = 0; b < block_count; ++b) {
    T sum{};
    const std::size_t first = static_cast<std::size_t>(b) * kBlockedSumBlock;
    const std::size_t end = std::min(count, first + kBlockedSumBlock);
    for (std::size_t c = first; c < end; ++c) term(c, sum);
    slots[b] = sum;
  }
  T sum{};
  for (const T& block : partial) sum += block;
  return sum;
}

}  // namespace tmdem::mechanics
