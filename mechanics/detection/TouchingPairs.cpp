#include "mechanics/detection/TouchingPairs.h"

#include <algorithm>
#include <cmath>

#include "mechanics/detection/CellGrid.h"

namespace tmdem::mechanics {
namespace {

// Particle pairs with gap <= threshold_fraction * min(r_i, r_j), sorted by (i, j).
std::vector<TouchingPair> particle_pairs_below(const ParticleSet& particles,
                                               double threshold_fraction) {
  std::vector<TouchingPair> pairs;
  if (particles.size() < 2) return pairs;
  // Two particles whose gap is below a fraction f of the smaller radius are closer than
  // 2 r_max (1 + max(f, 0)) centre to centre; cells of that size hold every such pair.
  const double reach = 2.0 * particles.max_radius() * (1.0 + std::max(threshold_fraction, 0.0));
  CellGrid grid;
  grid.build(particles.position, reach, particles.box);
  const auto& x = particles.position;
  const auto& r = particles.radius;
  const bool periodic = particles.box.any();
  grid.for_each_candidate_pair([&](std::uint32_t a, std::uint32_t b) {
    const Eigen::Vector3d d = x[a] - x[b];
    const double gap = (periodic ? particles.box.minimum_image(d) : d).norm() - r[a] - r[b];
    if (gap <= threshold_fraction * std::min(r[a], r[b])) {
      pairs.push_back({std::min(a, b), std::max(a, b), gap});
    }
  });
  std::sort(pairs.begin(), pairs.end(), [](const TouchingPair& p, const TouchingPair& q) {
    return p.i != q.i ? p.i < q.i : p.j < q.j;
  });
  return pairs;
}

}  // namespace

std::vector<TouchingPair> find_touching_pairs(const ParticleSet& particles,
                                              const std::vector<Wall>& walls,
                                              double gap_fraction) {
  std::vector<TouchingPair> pairs = particle_pairs_below(particles, gap_fraction);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const double gap = walls[w].signed_distance(particles.position[i]) - particles.radius[i];
      if (gap <= gap_fraction * particles.radius[i]) {
        pairs.push_back({static_cast<std::int64_t>(i), wall_code<std::int64_t>(w), gap});
      }
    }
  }
  return pairs;
}

std::vector<TouchingPair> find_overlaps(const ParticleSet& particles, double overlap_fraction) {
  std::vector<TouchingPair> pairs = particle_pairs_below(particles, -overlap_fraction);
  // particle_pairs_below keeps gap <= -f min(r); an overlap is strictly more than f min(r).
  std::erase_if(pairs, [&](const TouchingPair& p) {
    return !(p.gap_m < -overlap_fraction * std::min(particles.radius[p.i], particles.radius[p.j]));
  });
  return pairs;
}

}  // namespace tmdem::mechanics
