#pragma once
// How many OpenMP threads a loop over a thermal network's nodes uses. Small networks stay on
// one thread: a parallel region costs microseconds, which a loop over a few thousand nodes does
// not repay, and every scene of examples/ (at most a few thousand particles) keeps the bits of
// a one-thread run whatever OMP_NUM_THREADS says. From kThreadedNodes on, the thread count is
// OpenMP's (OMP_NUM_THREADS); each threaded loop says what it guarantees for its bits.
#include <omp.h>

#include <cstddef>

namespace tmdem::thermal {

inline constexpr std::size_t kThreadedNodes = 50000;

inline int node_loop_threads(std::size_t nodes) {
  return nodes >= kThreadedNodes ? omp_get_max_threads() : 1;
}

}  // namespace tmdem::thermal
