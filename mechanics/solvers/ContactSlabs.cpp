#include "mechanics/solvers/ContactSlabs.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {
namespace {

// A contact that writes a piston's velocity: every such contact shares that body.
bool on_piston(const ContactProblem& problem, std::size_t c) {
  const std::int32_t j = problem.body_j[c];
  return is_wall(j) && problem.inverse_mass[problem.wall_body(j)] > 0.0;
}

// x_i - x_j along the split axis, through the nearest image when the axis is periodic.
double branch(const ContactProblem& problem, std::size_t c) {
  const int a = problem.split_axis;
  const double d = problem.particle_position[static_cast<std::size_t>(problem.body_i[c])][a] -
                   problem.particle_position[static_cast<std::size_t>(problem.body_j[c])][a];
  if (!problem.split_periodic()) return d;
  const double L = problem.split_period[1] - problem.split_period[0];
  return d - L * std::round(d / L);
}

double midpoint(const ContactProblem& problem, std::size_t c) {
  const int a = problem.split_axis;
  const double xi = problem.particle_position[static_cast<std::size_t>(problem.body_i[c])][a];
  const std::int32_t j = problem.body_j[c];
  if (!problem.split_periodic())
    return is_wall(j) ? xi : 0.5 * (xi + problem.particle_position[static_cast<std::size_t>(j)][a]);
  // Halfway along the nearest image, back into the period.
  const double low = problem.split_period[0], L = problem.split_period[1] - low;
  const double m = is_wall(j) ? xi : xi - 0.5 * branch(problem, c);
  return m - L * std::floor((m - low) / L);
}

}  // namespace

bool ContactSlabs::update(const ContactProblem& problem, int slabs) {
  slab_start_.clear();
  phase_start_.clear();
  const std::size_t count = problem.size();
  if (problem.particle_position.size() != problem.particle_count || count == 0 || slabs < 3)
    return false;
  double span = 0.0, low = INFINITY, high = -INFINITY;
  for (std::size_t c = 0; c < count; ++c) {
    const std::int32_t j = problem.body_j[c];
    if (!is_wall(j)) span = std::max(span, std::abs(branch(problem, c)));
    if (on_piston(problem, c)) continue;
    const double x = midpoint(problem, c);
    low = std::min(low, x);
    high = std::max(high, x);
  }
  const bool periodic = problem.split_periodic();
  if (periodic) {
    // Round the period: slab 0 and the last are neighbours, so the count is even (the two
    // are then in different phases) and at least 4 (two slabs per phase).
    low = problem.split_period[0];
    high = problem.split_period[1];
  }
  if (!(high > low) || !std::isfinite(high - low)) return false;
  // A margin over the span, so that rounding in the division below cannot put two contacts of
  // one particle two slabs apart.
  double width = std::max(span * (1.0 + 1e-9), (high - low) / slabs);
  const double fit = std::floor((high - low) / width);
  auto cut = static_cast<std::int32_t>(std::min<double>(fit, slabs));
  if (periodic) {
    cut -= cut % 2;
    if (cut < 4) return false;
    width = (high - low) / cut;  // equal slabs filling the period, each at least as wide
  }
  if (cut < 3) return false;
  // Visiting order: even slabs, odd slabs, then one slab for a piston's contacts.
  const std::int32_t even = (cut + 1) / 2;
  auto visit_position = [&](std::int32_t slab) { return slab % 2 == 0 ? slab / 2 : even + slab / 2; };
  slab_of_.resize(count);
  for (std::size_t c = 0; c < count; ++c) {
    if (on_piston(problem, c)) {
      slab_of_[c] = cut;
      continue;
    }
    const double at = std::floor((midpoint(problem, c) - low) / width);
    slab_of_[c] = visit_position(static_cast<std::int32_t>(std::clamp<double>(at, 0.0, cut - 1)));
  }
  // Counting sort; contacts keep increasing index order inside a slab.
  slab_start_.assign(static_cast<std::size_t>(cut) + 2, 0);
  for (std::size_t c = 0; c < count; ++c) ++slab_start_[static_cast<std::size_t>(slab_of_[c]) + 1];
  for (std::size_t s = 0; s + 1 < slab_start_.size(); ++s) slab_start_[s + 1] += slab_start_[s];
  order_.resize(count);
  cursor_.assign(slab_start_.begin(), slab_start_.end() - 1);
  for (std::size_t c = 0; c < count; ++c)
    order_[static_cast<std::size_t>(cursor_[static_cast<std::size_t>(slab_of_[c])]++)] = static_cast<std::int32_t>(c);
  phase_start_ = {0, even, cut, cut + 1};
#ifndef NDEBUG
  // The promise, checked: the contacts of one particle lie in one slab or two neighbours (round
  // a period the last slab and the first are neighbours too).
  std::vector<std::int32_t> seen(problem.particle_count, -1), other(problem.particle_count, -1);
  for (std::size_t c = 0; c < count; ++c) {
    if (on_piston(problem, c)) continue;
    const std::int32_t v = slab_of_[c];
    const std::int32_t slab = v < even ? 2 * v : 2 * (v - even) + 1;
    for (const std::int32_t b : {problem.body_i[c], problem.body_j[c]}) {
      if (is_wall(b)) continue;
      const auto p = static_cast<std::size_t>(b);
      if (seen[p] < 0) seen[p] = slab;
      if (slab == seen[p] || slab == other[p]) continue;
      assert(other[p] < 0);  // a third slab
      other[p] = slab;
      const std::int32_t apart = std::abs(slab - seen[p]);
      assert(apart == 1 || (periodic && apart == cut - 1));
    }
  }
#endif
  return true;
}

}  // namespace tmdem::mechanics
