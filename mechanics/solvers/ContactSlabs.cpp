#include "mechanics/solvers/ContactSlabs.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

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

// Likely to be visited by the partial sweeps too (GaussSeidelSweep's active sets: 3 sweeps in
// 4 visit only the closed contacts): touching or overlapping. Open look-ahead candidates
// (pour_3d: 92% of them) are visited by the full sweeps only.
std::int64_t ContactSlabs::visit_weight(const ContactProblem& problem, std::size_t c) {
  return problem.bias[c] <= 0.0 ? 4 : 1;
}

void ContactSlabs::cut_boundaries(const ContactProblem& problem, double low, double high,
                                  double min_width, std::int32_t cut) {
  // Slabs of about equal work (visits per sweep, weighed by visit_weight), not equal width: a
  // phase's slabs then keep its threads equally long. A histogram of the contacts' midpoints,
  // kBins a slab, gives the boundaries at its bins' edges; each slab stays at least min_width
  // wide (and leaves the slabs after it room for theirs), so where the work crowds into less
  // than that the slab is wider than its share.
  const std::size_t bins = kBins * static_cast<std::size_t>(cut);
  const double bin_width = (high - low) / double(bins);
  work_.assign(bins, 0);
  std::int64_t total = 0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (slab_of_[c] >= 0) continue;  // the last phase's
    const double at = std::floor((midpoint_[c] - low) / bin_width);
    const auto bin = static_cast<std::size_t>(std::clamp<double>(at, 0.0, double(bins - 1)));
    const std::int64_t w = visit_weight(problem, c);
    work_[bin] += w;
    total += w;
  }
  boundary_.assign(static_cast<std::size_t>(cut) + 1, low);
  boundary_.back() = high;
  std::int64_t below = 0;  // the work left of `edge`
  std::size_t edge = 0;
  for (std::int32_t s = 1; s < cut; ++s) {
    const std::int64_t target = total * s / cut;
    while (edge < bins && below + work_[edge] <= target) below += work_[edge++];
    double x = low + double(edge) * bin_width;
    x = std::max(x, boundary_[static_cast<std::size_t>(s) - 1] + min_width);
    x = std::min(x, high - double(cut - s) * min_width);
    boundary_[static_cast<std::size_t>(s)] = x;
  }
}

std::int32_t ContactSlabs::slab_at(double x) const {
  // boundary_[s] <= x < boundary_[s + 1]; beyond the ends, the end slabs.
  const auto past = std::upper_bound(boundary_.begin() + 1, boundary_.end() - 1, x);
  return static_cast<std::int32_t>(past - (boundary_.begin() + 1));
}

bool ContactSlabs::update(const ContactProblem& problem, int slabs) {
  slab_start_.clear();
  phase_start_.clear();
  const std::size_t count = problem.size();
  if (problem.particle_position.size() != problem.particle_count || count == 0 || slabs < 3)
    return false;
  // The reach of a touching pair: no contact that can close within the step is longer along
  // the axis. Look-ahead candidates between particles further apart (fast ones: the falling
  // spheres of a pour) would widen every slab: at 4.8 mm for pour_3d's 2 mm spheres its 19 mm
  // fitted 3 slabs, whose odd phase of one slab left a second thread nothing to do.
  double reach = 0.0;
  for (std::size_t c = 0; c < count; ++c)
    if (!is_wall(problem.body_j[c])) reach = std::max(reach, problem.lever_i[c] + problem.lever_j[c]);
  reach *= 1.0 + 1e-9;
  // slab_of_: -1 for the slabs' contacts (placed below), the last phase for a piston's and the
  // long candidates (one thread, after the others).
  slab_of_.assign(count, -1);
  midpoint_.resize(count);  // of the slabs' contacts, for the histogram and the placing
  std::size_t last_phase = 0;
  double span = 0.0, low = INFINITY, high = -INFINITY;
  for (std::size_t c = 0; c < count; ++c) {
    const std::int32_t j = problem.body_j[c];
    const double length = is_wall(j) ? 0.0 : std::abs(branch(problem, c));
    if (on_piston(problem, c) || length > reach) {
      slab_of_[c] = std::numeric_limits<std::int32_t>::max();
      ++last_phase;
      continue;
    }
    span = std::max(span, length);
    const double x = midpoint_[c] = midpoint(problem, c);
    low = std::min(low, x);
    high = std::max(high, x);
  }
  // Slabs only where most contacts are in them (a bed that is nearly all look-ahead: swept in
  // the problem's order).
  if (2 * last_phase > count) return false;
  const bool periodic = problem.split_periodic();
  if (periodic) {
    // Round the period: slab 0 and the last are neighbours, so the count is even (the two
    // are then in different phases) and at least 4 (two slabs per phase).
    low = problem.split_period[0];
    high = problem.split_period[1];
  }
  if (!(high > low) || !std::isfinite(high - low)) return false;
  // A margin over the span, so that rounding cannot put two contacts of one particle two slabs
  // apart: every slab is at least this wide.
  const double min_width = span * (1.0 + 1e-9);
  const double fit = std::floor((high - low) / std::max(min_width, (high - low) / slabs));
  auto cut = static_cast<std::int32_t>(std::min<double>(fit, slabs));
  // An even count per phase from 4 slabs on (a multiple of 4): the two threads of a 2-core
  // machine then share each phase's slabs evenly (5 slabs: the even phase's 3 go 2 + 1).
  if (cut >= 4) cut -= cut % 4;
  if (periodic && cut < 4) return false;
  if (cut < 3) return false;
  cut_boundaries(problem, low, high, min_width, cut);
  // Visiting order: even slabs, odd slabs, then one slab for a piston's contacts and the long
  // candidates.
  const std::int32_t even = (cut + 1) / 2;
  auto visit_position = [&](std::int32_t slab) { return slab % 2 == 0 ? slab / 2 : even + slab / 2; };
  for (std::size_t c = 0; c < count; ++c)
    slab_of_[c] = slab_of_[c] >= 0 ? cut : visit_position(slab_at(midpoint_[c]));
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
    const std::int32_t v = slab_of_[c];
    if (v == cut) continue;  // the last phase, on one thread
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
