#pragma once
// Each wall's force, N: the normal forces of the contacts with it summed in the contacts' order
// (a pair's j < 0 names wall -1 - j, mechanics/model/PairIndex.h). The result file's
// /frames/wall_force and the coupled summary's wall forces are this sum.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace tmdem::coupling {

// force_N (sized to the walls already) = per wall, the sum over the contacts (pair: 2 per
// contact, i and j) of normal_force_N; no allocation.
inline void sum_wall_forces(std::span<const std::int64_t> pair, std::span<const double> normal_force_N,
                            std::vector<double>& force_N) {
  std::fill(force_N.begin(), force_N.end(), 0.0);
  for (std::size_t k = 0; k < normal_force_N.size(); ++k) {
    const std::int64_t j = pair[2 * k + 1];
    if (j < 0 && std::size_t(-1 - j) < force_N.size()) force_N[std::size_t(-1 - j)] += normal_force_N[k];
  }
}

}  // namespace tmdem::coupling
