#pragma once
// The problem size (particles, candidates or contacts) from which the mechanics' loops use
// OpenMP threads: below it, waking the threads costs more than the loop. One value for every
// loop: NscdParameters::parallel_from carries it to the detection, the contact set-up and,
// through SolverSettings::parallel_from, the contact solvers (0: threads at any size, for
// tests). Every loop gives the same bits whatever the thread count.
#include <cstddef>

namespace tmdem::mechanics {

inline constexpr std::ptrdiff_t kDefaultParallelFrom = 4096;

}  // namespace tmdem::mechanics
