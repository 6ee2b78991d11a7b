#include "mechanics/integrator/StaticWarmStart.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace tmdem::mechanics {

namespace {
// Touching: a gap of at most this fraction of the first sphere's radius (a deposited bed's
// contacts are exact to round-off; an imported one's overlap). At |g| h^2 (10 um at 1 ms) the
// deposited 10,000 bed took 27,115 contacts into its first step instead of 26,554, and the
// step took longer than from zero impulses.
constexpr double kTouchingGapFraction = 1e-6;
}  // namespace

void static_warm_start(const ContactProblem& problem, const std::vector<double>& gap_m,
                       const std::vector<Eigen::Vector3d>& positions_m,
                       const Eigen::Vector3d& gravity_m_per_s2, double h_s,
                       std::vector<Eigen::Vector3d>& reactions) {
  const std::size_t contacts = problem.size();
  const std::size_t n = problem.particle_count;
  reactions.assign(contacts, Eigen::Vector3d::Zero());
  const double g = gravity_m_per_s2.norm();
  if (!(g > 0.0) || n == 0) return;
  const Eigen::Vector3d up = -gravity_m_per_s2 / g;

  // Each particle's touching contacts (CSR).
  std::vector<std::size_t> start(n + 1, 0);
  auto touching = [&](std::size_t c) {
    return problem.solvable(c) && gap_m[c] <= kTouchingGapFraction * problem.lever_i[c];
  };
  // Contacts that join clusters (below): touching, or closed by a fall from rest within the
  // step (a gap up to |g| h^2, 10 um at 1 ms), so that a bed a hair above its floor (an
  // imported one) counts as held; a bed 1 mm above it does not.
  const double reach_m = g * h_s * h_s;
  auto within_reach = [&](std::size_t c) {
    return problem.solvable(c) && (gap_m[c] <= reach_m || touching(c));
  };
  for (std::size_t c = 0; c < contacts; ++c) {
    if (!touching(c)) continue;
    ++start[std::size_t(problem.body_i[c]) + 1];
    if (!is_wall(problem.body_j[c])) ++start[std::size_t(problem.body_j[c]) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1), of(start[n]);
  for (std::size_t c = 0; c < contacts; ++c) {
    if (!touching(c)) continue;
    of[fill[std::size_t(problem.body_i[c])]++] = c;
    if (!is_wall(problem.body_j[c])) of[fill[std::size_t(problem.body_j[c])]++] = c;
  }

  // Highest first; equal heights by index, so the order is the same on every machine.
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> height(n);
  for (std::size_t i = 0; i < n; ++i) height[i] = up.dot(positions_m[i]);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return height[std::size_t(a)] != height[std::size_t(b)] ? height[std::size_t(a)] > height[std::size_t(b)]
                                                             : a < b;
  });
  std::vector<std::size_t> rank(n);
  for (std::size_t r = 0; r < n; ++r) rank[std::size_t(order[r])] = r;

  // A particle's touching contact c with a body below it, and how far its normal into i
  // points up (> 0 for a support; 0 when c is no support of i).
  const auto support_rise = [&](std::size_t i, std::size_t r, std::size_t c) {
    const bool first = std::size_t(problem.body_i[c]) == i;
    const double along_up = (first ? 1.0 : -1.0) * problem.normal[c].dot(up);
    const std::int32_t other = first ? problem.body_j[c] : problem.body_i[c];
    const bool below = is_wall(other) || !(problem.inverse_mass[std::size_t(other)] > 0.0) ||
                       rank[std::size_t(other)] > r;
    return below && along_up > 0.0 ? along_up : 0.0;
  };
  const auto other_body = [&](std::size_t i, std::size_t c) {
    return std::size_t(problem.body_i[c]) == i ? problem.body_j[c] : problem.body_i[c];
  };
  // Held: in a cluster of particles (joined by contacts within reach) that reaches a wall or a
  // fixed particle. A cluster that reaches neither (a bed deposited above the floor, a heap in
  // the air) is falling, and its contacts carry nothing: loads passed down into it had no
  // floor to end on, and the lowest spheres of a bed deposited 1 mm above the floor took the
  // bed's weight as a downward impulse, from which the first step's solver diverged (speeds
  // of 1e10 m/s, periodic_pressed.toml raised by 1 mm). A held cluster is passed its loads
  // as before, whichever way it is held: a sphere wedged by friction beside the wall of a
  // settled bed has no support below it and still rests (held to chains of supports that end
  // on a wall, such a bed, imported back, moved 150 times more over its first second).
  std::vector<std::size_t> root(n);
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  std::vector<char> reaches_immobile(n, 0);
  for (std::size_t i = 0; i < n; ++i) reaches_immobile[i] = !(problem.inverse_mass[i] > 0.0);
  for (std::size_t c = 0; c < contacts; ++c) {
    if (!within_reach(c)) continue;
    const auto i = std::size_t(problem.body_i[c]);
    if (is_wall(problem.body_j[c])) {
      reaches_immobile[i] = 1;
      continue;
    }
    const std::size_t a = find(i), b = find(std::size_t(problem.body_j[c]));
    if (a != b) root[a] = b;
  }
  std::vector<char> held(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (reaches_immobile[i]) held[find(i)] = 1;
  for (std::size_t i = 0; i < n; ++i) held[i] = held[find(i)];

  // Vertical load on each particle, N: its weight, and what the particles above pass down.
  std::vector<double> load_N(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (problem.inverse_mass[i] > 0.0) load_N[i] = g / problem.inverse_mass[i];
  std::vector<std::size_t> supports;
  std::vector<double> rise;  // each support's normal . up, > 0
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = std::size_t(order[r]);
    if (!(problem.inverse_mass[i] > 0.0)) continue;  // fixed: carries like a wall
    if (!held[i]) continue;                           // falling with its whole cluster
    supports.clear();
    rise.clear();
    double rise_squared = 0.0;
    for (std::size_t s = start[i]; s < start[i + 1]; ++s) {
      const std::size_t c = of[s];
      const double along_up = support_rise(i, r, c);
      if (!(along_up > 0.0)) continue;
      supports.push_back(c);
      rise.push_back(along_up);
      rise_squared += along_up * along_up;
    }
    // The least-norm forces whose vertical parts carry the load: f_k = V a_k / |a|^2.
    for (std::size_t k = 0; k < supports.size(); ++k) {
      const std::size_t c = supports[k];
      const double force_N = load_N[i] * rise[k] / rise_squared;
      reactions[c] = Eigen::Vector3d(force_N * h_s, 0.0, 0.0);
      const std::int32_t other = other_body(i, c);
      if (!is_wall(other)) load_N[std::size_t(other)] += force_N * rise[k];
    }
  }
}

}  // namespace tmdem::mechanics
