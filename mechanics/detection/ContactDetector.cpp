#include "mechanics/detection/ContactDetector.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace tmdem::mechanics {
namespace {

bool pair_less(const CandidatePair& a, const CandidatePair& b) {
  return a.i != b.i ? a.i < b.i : a.j < b.j;
}

// The two largest of a series of lengths, summed: the most any pair of particles can move
// apart when each moves at most its own length.
struct LargestTwo {
  double first = 0.0, second = 0.0;
  void add(double x) {
    if (x > first) {
      second = first;
      first = x;
    } else if (x > second) {
      second = x;
    }
  }
  double sum() const { return first + second; }
};

}  // namespace

ContactDetector::ContactDetector(double min_margin_m, double max_margin_m,
                                 std::ptrdiff_t parallel_from)
    : min_margin_(min_margin_m), max_margin_(max_margin_m), parallel_from_(parallel_from) {
  grid_.set_parallel_from(parallel_from);
  if (!(min_margin_m > 0.0) || !(max_margin_m >= min_margin_m) || !std::isfinite(max_margin_m)) {
    throw std::invalid_argument("ContactDetector: need 0 < min_margin <= max_margin");
  }
}

void ContactDetector::restore(double margin_m, std::size_t rebuilds,
                              std::vector<Eigen::Vector3d> reference_m,
                              std::vector<CandidatePair> pairs,
                              std::vector<Eigen::Vector3d> reference_wall_points_m,
                              double wall_margin_m, bool widened_by_wall) {
  for (std::size_t p = 1; p < pairs.size(); ++p)
    if (!pair_less(pairs[p - 1], pairs[p]))
      throw std::invalid_argument("ContactDetector::restore: pairs not in strictly increasing (i, j) order");
  margin_ = margin_m;
  wall_margin_ = wall_margin_m > 0.0 ? wall_margin_m : margin_m;
  widened_by_wall_ = widened_by_wall;
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
                             const std::vector<double>& wall_lookahead_m,
                             const std::vector<double>& periodic_lookahead_m) {
  const std::size_t n = particles.size();
  double lookahead_max = 0.0;
  double periodic_pair_lookahead = 0.0;  // the two largest look-aheads across the periods, summed
  bool need = !valid_ || reference_position_.size() != n;
  // Serial on purpose: about 3 ns per particle, less than waking threads costs on a loaded
  // machine (measured: 100,000 particles, 0.3 ms serial, 1 to 20 ms with 2 threads at load 11).
  const PeriodicBox& box = particles.box;
  // A moving wall that can touch a particle within the coming step (engaged) may hand its speed
  // to the bed (a piston landing at 7 m/s): any particle may then move as far as the wall within
  // the step, so each is held to the displacement test with at least the wall's look-ahead, and
  // the particles' pairs are listed within its reach (as all pairs were before walls had a
  // margin of their own). A wall that touches nothing this step hands nothing on. Why each
  // particle: a landing taken in parts (NscdIntegrator::step) kicks spheres at rest, whose own
  // look-aheads are nil, across pairs a table listed a few parts before. (On periodic_pressed
  // the runs with and without this hold were the same: its tables were rebuilt for other
  // reasons. It is kept because the bound the table relies on needs it.)
  const double engaged_lookahead_max = engaged_wall_lookahead(particles, walls, lookahead_m, wall_lookahead_m);
  if (!box.any()) {
    for (std::size_t i = 0; i < n; ++i) {
      const double ahead = lookahead_m.empty() ? 0.0 : lookahead_m[i];
      lookahead_max = std::max(lookahead_max, ahead);
      if (!need && (particles.position[i] - reference_position_[i]).norm() + std::max(ahead, engaged_lookahead_max) >
                       0.5 * margin_)
        need = true;
    }
  } else {
    // Through the nearest image: a particle wrapped across a periodic boundary has moved by
    // its displacement, not by the period. Two tests (see the header): each particle within
    // half the listing margin, and every pair's motion across the periods (the sum of the two
    // particles' displacements and look-aheads along the periodic axes) within the fitted
    // margin, which the two largest decide.
    const double fitted_m = fitted_margin_m(particles);
    LargestTwo across_reach, across_ahead;
    for (std::size_t i = 0; i < n; ++i) {
      const double ahead = lookahead_m.empty() ? 0.0 : lookahead_m[i];
      const double periodic_ahead = periodic_lookahead_m.empty() ? ahead : periodic_lookahead_m[i];
      lookahead_max = std::max(lookahead_max, ahead);
      across_ahead.add(periodic_ahead);
      if (need) continue;
      const Eigen::Vector3d moved = box.minimum_image(particles.position[i] - reference_position_[i]);
      if (moved.norm() + std::max(ahead, engaged_lookahead_max) > 0.5 * margin_) need = true;
      across_reach.add(box.norm_across(moved) + periodic_ahead);
    }
    if (across_reach.sum() > fitted_m) need = true;
    periodic_pair_lookahead = across_ahead.sum();
  }
  // A restored table without wall points takes today's (fixed walls never move).
  if (reference_wall_point_.size() != walls.size()) {
    reference_wall_point_.clear();
    for (const auto& w : walls) reference_wall_point_.push_back(w.point);
  }
  double wall_lookahead_max = 0.0;
  for (std::size_t w = 0; w < wall_lookahead_m.size() && w < walls.size(); ++w) {
    wall_lookahead_max = std::max(wall_lookahead_max, wall_lookahead_m[w]);
    if ((walls[w].point - reference_wall_point_[w]).norm() + wall_lookahead_m[w] > 0.5 * wall_margin_)
      need = true;
  }
  const double reach_lookahead_max = std::max(lookahead_max, engaged_lookahead_max);
  // An engaged wall the particles' margin does not cover: list their pairs within its reach now.
  if (engaged_lookahead_max > 0.0 && 2.0 * engaged_lookahead_max > margin_) need = true;
  // A table a landing wall widened outlives the landing: the piston stops within a few steps,
  // the particles barely move under it, so no displacement ever asks for a rebuild, and every
  // step after the landing kept all the pairs within the landing's reach (periodic_pressed:
  // 500,500 candidates, 35-50 s a step). Such a table is rebuilt once its margin is 2x what the
  // look-aheads now ask, and again as the bed the landing shook slows down (a shrinking table
  // stays marked), until a rebuild the displacements ask for ends the chain. Only after a
  // wall's widening: tried on every table, it also rebuilt piles coming to rest in the tests and
  // changed their problems.
  const bool shrink = !need && widened_by_wall_ && margin_ > 2.0 * margin_for(reach_lookahead_max);
  if (shrink) need = true;
  if (!need) return false;
  widened_by_wall_ = engaged_lookahead_max > lookahead_max || shrink;
  rebuild(particles, walls, reach_lookahead_max, wall_lookahead_max);
  if (particles.box.any()) check_period(particles, periodic_pair_lookahead);
  return true;
}

bool ContactDetector::covers(const ParticleSet& particles, const std::vector<Eigen::Vector3d>& travel_m,
                             const std::vector<Wall>& walls, const std::vector<double>& wall_travel_m) const {
  const std::size_t n = particles.size();
  if (!valid_ || reference_position_.size() != n || travel_m.size() < n) return false;
  const PeriodicBox& box = particles.box;
  LargestTwo across;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d moved = particles.position[i] + travel_m[i] - reference_position_[i];
    if (box.any()) moved = box.minimum_image(moved);
    if (moved.norm() > 0.5 * margin_) return false;
    if (box.any()) across.add(box.norm_across(moved));
  }
  if (box.any() && across.sum() > fitted_margin_m(particles)) return false;
  if (reference_wall_point_.size() != walls.size()) return false;
  for (std::size_t w = 0; w < walls.size() && w < wall_travel_m.size(); ++w) {
    const Eigen::Vector3d moved = walls[w].point + wall_travel_m[w] * walls[w].normal - reference_wall_point_[w];
    if (moved.norm() > 0.5 * wall_margin_) return false;
  }
  return true;
}

double ContactDetector::engaged_wall_lookahead(const ParticleSet& particles, const std::vector<Wall>& walls,
                                               const std::vector<double>& lookahead_m,
                                               const std::vector<double>& wall_lookahead_m) const {
  double engaged = 0.0;
  for (std::size_t w = 0; w < wall_lookahead_m.size() && w < walls.size(); ++w) {
    if (wall_lookahead_m[w] > engaged && wall_engaged(particles, walls[w], wall_lookahead_m[w], lookahead_m))
      engaged = wall_lookahead_m[w];
  }
  return engaged;
}

bool ContactDetector::wall_engaged(const ParticleSet& particles, const Wall& wall, double wall_lookahead_m,
                                   const std::vector<double>& lookahead_m) const {
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double ahead = lookahead_m.empty() ? 0.0 : lookahead_m[i];
    const double distance = wall.signed_distance(particles.position[i]);
    // A centre behind the wall is not the wall's to touch (a sphere parked beyond a piston).
    if (distance >= 0.0 && distance - particles.radius[i] <= wall_lookahead_m + ahead) return true;
  }
  return false;
}

double ContactDetector::fitted_margin_m(const ParticleSet& particles) const {
  // The nearest image is the only one that can touch while a pair's relative motion across the
  // periods between rebuilds stays below half a period less a diameter; past that a pair could
  // touch twice (two images), which one candidate cannot hold.
  return 0.5 * particles.box.shortest_period() - 2.0 * particles.max_radius();
}

bool ContactDetector::fits_periods(const ParticleSet& particles,
                                   const std::vector<double>& periodic_lookahead_m) const {
  if (!particles.box.any()) return true;
  LargestTwo ahead;
  for (const double a : periodic_lookahead_m) ahead.add(a);
  return pair_fits_periods(particles, ahead.sum());
}

bool ContactDetector::pair_fits_periods(const ParticleSet& particles, double pair_lookahead_m) const {
  const double fitted_m = fitted_margin_m(particles);
  return fitted_m > 0.0 && fitted_m >= pair_lookahead_m;
}

void ContactDetector::check_period(const ParticleSet& particles, double pair_lookahead_m) const {
  // The test across the periods is sound only while the two largest look-aheads across them
  // fit in the fitted margin together: a rebuild cannot help beyond that.
  if (pair_fits_periods(particles, pair_lookahead_m)) return;
  const double fitted_m = fitted_margin_m(particles);
  const double period_m = particles.box.shortest_period();
  // Significant digits, not std::to_string's six decimals (a look-ahead of 2e-7 m printed as
  // 0.000000 m).
  std::ostringstream message;
  message << "a periodic period is too short for the contact reach: half the shortest period "
             "less the largest diameter leaves "
          << fitted_m << " m, less than the two largest look-aheads along the periodic axes together, "
          << pair_lookahead_m << " m (how far two particles may move apart across the period in a step)";
  // A look-ahead beyond a whole period is a particle crossing the box within a step: a speed no
  // period could hold, left by a step that went wrong before (a bed deposited 1 mm above its
  // floor had its first contact solve diverge to 1e10 m/s, and this message asked for a longer
  // period than 9e7 m).
  if (pair_lookahead_m >= period_m)
    message << ", longer than the whole period " << period_m
            << " m: a particle that fast points to an earlier step that went wrong (an "
               "unconverged contact solve, see the warnings above), not to the period";
  else
    message << ": enlarge the period or shorten mechanics.time_step";
  throw std::runtime_error(message.str());
}

void ContactDetector::rebuild(const ParticleSet& particles, const std::vector<Wall>& walls,
                              double lookahead_max, double wall_lookahead_max) {
  const std::size_t n = particles.size();
  // Two particles can close by at most the sum of their look-aheads before the next check,
  // so the margin is never below twice the largest one, whatever max_margin says: a fast
  // particle widens the table rather than tunnel through an unlisted neighbour or wall.
  margin_ = margin_for(lookahead_max);
  // A moving wall's pairs: the same rule on its own look-ahead, never below the particles'
  // margin (a particle-wall gap closes by both displacements; see the header).
  wall_margin_ = std::max(margin_, margin_for(wall_lookahead_max));
  std::swap(pairs_, previous_pairs_);
  const auto& x = particles.position;
  const auto& r = particles.radius;
  const auto& fixed = particles.fixed;
  const auto count = static_cast<std::ptrdiff_t>(n);
  const PeriodicBox& box = particles.box;
  const bool periodic = box.any();
  if (n >= 2) grid_.build(x, 2.0 * particles.max_radius() + margin_, box);
  const bool parallel = count >= parallel_from_;
  const auto threads = static_cast<std::size_t>(parallel ? omp_get_max_threads() : 1);
  if (thread_pairs_.size() < threads) {
    thread_pairs_.resize(threads);
    thread_neighbours_.resize(threads);
  }
#pragma omp parallel if (parallel)
  {
    const auto team = static_cast<std::ptrdiff_t>(omp_get_num_threads());
    const auto t = static_cast<std::ptrdiff_t>(omp_get_thread_num());
    auto& local = thread_pairs_[t];
    auto& neighbours = thread_neighbours_[t];
    local.clear();
    // Table order: for each i, walls first (j = -1 - w ascending, i.e. w descending), then
    // particles j > i ascending.
    for (std::ptrdiff_t i = count * t / team; i < count * (t + 1) / team; ++i) {
      const auto a = static_cast<std::uint32_t>(i);
      const auto ii = static_cast<std::int32_t>(i);
      if (!fixed[a]) {
        for (std::size_t w = walls.size(); w-- > 0;) {
          if (walls[w].signed_distance(x[a]) - r[a] <= (walls[w].moves() ? wall_margin_ : margin_)) {
            local.push_back({ii, wall_code<std::int32_t>(w)});
          }
        }
      }
      if (n < 2) continue;
      neighbours.clear();
      const auto collect = [&](auto&& distance_squared) {
        grid_.for_each_neighbour(a, [&](std::uint32_t b) {
          if (b < a || (fixed[a] && fixed[b])) return;  // fixed bodies never exchange impulses
          const double reach = r[a] + r[b] + margin_;
          if (distance_squared(b) <= reach * reach) neighbours.push_back(b);
        });
      };
      if (periodic)
        collect([&](std::uint32_t b) { return box.minimum_image(x[a] - x[b]).squaredNorm(); });
      else
        collect([&](std::uint32_t b) { return (x[a] - x[b]).squaredNorm(); });
      std::sort(neighbours.begin(), neighbours.end());
      for (const std::uint32_t b : neighbours) local.push_back({ii, static_cast<std::int32_t>(b)});
    }
#pragma omp barrier
#pragma omp single
    {
      std::size_t total = 0;
      for (std::ptrdiff_t k = 0; k < team; ++k) total += thread_pairs_[k].size();
      pairs_.resize(total);
    }
    std::size_t offset = 0;
    for (std::ptrdiff_t k = 0; k < t; ++k) offset += thread_pairs_[k].size();
    std::copy(local.begin(), local.end(), pairs_.begin() + static_cast<std::ptrdiff_t>(offset));
  }

  // Match against the previous table (both sorted) so reactions can be warm-started.
  previous_index_.resize(pairs_.size());
  const auto listed = static_cast<std::ptrdiff_t>(pairs_.size());
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < listed; ++p) {
    const auto k = std::lower_bound(previous_pairs_.begin(), previous_pairs_.end(), pairs_[p], pair_less);
    const bool same = k != previous_pairs_.end() && k->i == pairs_[p].i && k->j == pairs_[p].j;
    previous_index_[p] = same ? static_cast<std::int32_t>(k - previous_pairs_.begin()) : -1;
  }

  reference_position_.assign(x.begin(), x.end());
  reference_wall_point_.clear();
  for (const auto& w : walls) reference_wall_point_.push_back(w.point);
  valid_ = true;
  ++rebuilds_;
}

}  // namespace tmdem::mechanics
