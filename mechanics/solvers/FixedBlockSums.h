#pragma once
// Deterministic parallel sums (ApgdSolver, ColouredGaussSeidelSolver): each thread sums whole
// blocks of kSumBlock contacts into its block's slots, then the block sums are added in
// block order, so a total is the same bits for any thread count.

#include <array>
#include <cstddef>
#include <vector>

namespace tmdem::mechanics {

inline constexpr std::ptrdiff_t kSumBlock = 256;  // contacts per block

inline std::ptrdiff_t sum_block_count(std::ptrdiff_t contacts) {
  return (contacts + kSumBlock - 1) / kSumBlock;
}

// partial holds Sums numbers per block, block after block; returns the Sums totals.
template <std::size_t Sums>
std::array<double, Sums> add_block_sums(const std::vector<double>& partial, std::ptrdiff_t blocks) {
  std::array<double, Sums> total{};
  for (std::ptrdiff_t block = 0; block < blocks; ++block) {
    for (std::size_t s = 0; s < Sums; ++s) total[s] += partial[Sums * static_cast<std::size_t>(block) + s];
  }
  return total;
}

}  // namespace tmdem::mechanics
