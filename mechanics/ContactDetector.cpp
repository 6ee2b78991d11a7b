#include "mechanics/ContactDetector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tmdem::mechanics {
namespace {

bool pair_less(const CandidatePair& a, const CandidatePair& b) {
  return a.i != b.i ? a.i < b.i : a.j < b.j;
}

}  // namespace

ContactDetector::ContactDetector(double min_margin_m, double max_margin_m)
    : min_margin_(min_margin_m), max_margin_(max_margin_m) {
  if (!(min_margin_m > 0.0) || !(max_margin_m >= min_margin_m) || !std::isfinite(max_margin_m)) {
    throw std::invalid_argument("ContactDetector: need 0 < min_margin <= max_margin");
  }
}

void ContactDetector::restore(double margin_m, std::size_t rebuilds,
                              std::vector<Eigen::Vector3d> reference_m,
                              std::vector<CandidatePair> pairs,
                              std::vector<Eigen::Vector3d> reference_wall_points_m) {
  for (std::size_t p = 1; p < pairs.size(); ++p)
    if (!pair_less(pairs[p - 1], pairs[p]))
      throw std::invalid_argument("ContactDetector::restore: pairs not in strictly increasing (i, j) order");
  margin_ = margin_m;
  rebuilds_ = rebuilds;
  valid_ = !reference_m.empty();
  reference_position_ = std::move(reference_m);
  pairs_ = std::move(pairs);
  reference_wall_point_ = std::move(reference_wall_points_m);
  previous_pairs_.clear();
  previous_index_.clear();
}

bool ContactDetector::update(const ParticleSet& particles, const std::vector<Wall>& walls,
                             const std::vector<double>& lookahead_m,
                             const std::vector<double>& wall_lookahead_m) {
  const std::size_t n = particles.size();
  double lookahead_max = 0.0;
  bool need = !valid_ || reference_position_.size() != n;
  for (std::size_t i = 0; i < n; ++i) {
    const double ahead = lookahead_m.empty() ? 0.0 : lookahead_m[i];
    lookahead_max = std::max(lookahead_max, ahead);
    if (!need && (particles.position[i] - reference_position_[i]).norm() + ahead > 0.5 * margin_) {
      need = true;
    }
  }
  // A restored table without wall points takes today's (fixed walls never move).
  if (reference_wall_point_.size() != walls.size()) {
    reference_wall_point_.clear();
    for (const auto& w : walls) reference_wall_point_.push_back(w.point);
  }
  for (std::size_t w = 0; w < wall_lookahead_m.size() && w < walls.size(); ++w) {
    lookahead_max = std::max(lookahead_max, wall_lookahead_m[w]);
    if ((walls[w].point - reference_wall_point_[w]).norm() + wall_lookahead_m[w] > 0.5 * margin_)
      need = true;
  }
  if (!need) return false;
  rebuild(particles, walls, lookahead_max);
  return true;
}

void ContactDetector::rebuild(const ParticleSet& particles, const std::vector<Wall>& walls,
                              double lookahead_max) {
  const std::size_t n = particles.size();
  // Two particles can close by at most the sum of their look-aheads before the next check,
  // so the margin is never below twice the largest one, whatever max_margin says: a fast
  // particle widens the table rather than tunnel through an unlisted neighbour or wall.
  margin_ = std::max(std::clamp(4.0 * lookahead_max, min_margin_, max_margin_),
                     2.0 * lookahead_max);
  std::swap(pairs_, previous_pairs_);
  pairs_.clear();
  const auto& x = particles.position;
  const auto& r = particles.radius;
  const auto& fixed = particles.fixed;
  if (n >= 2) {
    grid_.build(x, 2.0 * particles.max_radius() + margin_);
    grid_.for_each_candidate_pair([&](std::uint32_t a, std::uint32_t b) {
      if (fixed[a] && fixed[b]) return;  // two fixed bodies never exchange impulses
      const double reach = r[a] + r[b] + margin_;
      if ((x[a] - x[b]).squaredNorm() <= reach * reach) {
        pairs_.push_back({static_cast<std::int32_t>(std::min(a, b)),
                          static_cast<std::int32_t>(std::max(a, b))});
      }
    });
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (fixed[i]) continue;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (walls[w].signed_distance(x[i]) - r[i] <= margin_) {
        pairs_.push_back({static_cast<std::int32_t>(i), wall_code<std::int32_t>(w)});
      }
    }
  }
  std::sort(pairs_.begin(), pairs_.end(), pair_less);

  // Match against the previous table (both sorted) so reactions can be warm-started.
  previous_index_.resize(pairs_.size());
  std::size_t k = 0;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    while (k < previous_pairs_.size() && pair_less(previous_pairs_[k], pairs_[p])) ++k;
    const bool same = k < previous_pairs_.size() && previous_pairs_[k].i == pairs_[p].i &&
                      previous_pairs_[k].j == pairs_[p].j;
    previous_index_[p] = same ? static_cast<std::int32_t>(k) : -1;
  }

  reference_position_.assign(x.begin(), x.end());
  reference_wall_point_.clear();
  for (const auto& w : walls) reference_wall_point_.push_back(w.point);
  valid_ = true;
  ++rebuilds_;
}

}  // namespace tmdem::mechanics
