#pragma once
// Geometry-only contact search, for runs without mechanics (effects.mechanics = "off") and
// for rejecting scenes whose particles overlap at start. Uses the cell grid: O(N).
//
// Pair convention (same as the result file): i is a particle id; j is a particle id with
// i < j, or a wall encoded as in mechanics/model/PairIndex.h.

#include <cstdint>
#include <vector>

#include "mechanics/model/PairIndex.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/model/Wall.h"

namespace tmdem::mechanics {

struct TouchingPair {
  std::int64_t i = 0;  // particle id
  std::int64_t j = 0;  // particle id (> i) or wall_code(wall) (PairIndex.h)
  double gap_m = 0.0;  // distance - r_i - r_j (wall: signed distance - r_i); < 0 = overlap
};

// Pairs that touch: particle pairs whose gap is at most gap_fraction * min(r_i, r_j) and
// particle-wall pairs whose gap is at most gap_fraction * r_i (overlapping pairs included).
// Order: particle pairs sorted by (i, j), then wall pairs sorted by (i, wall).
std::vector<TouchingPair> find_touching_pairs(const ParticleSet& particles,
                                              const std::vector<Wall>& walls,
                                              double gap_fraction = 1e-9);

// Particle pairs that overlap by more than overlap_fraction of the smaller radius
// (gap < -overlap_fraction * min(r_i, r_j)), sorted by (i, j). Walls are not checked.
std::vector<TouchingPair> find_overlaps(const ParticleSet& particles,
                                        double overlap_fraction = 1e-9);

}  // namespace tmdem::mechanics
