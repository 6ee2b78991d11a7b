#include "mechanics/integrator/StaticWarmStart.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cstdint>
#include <numeric>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/solvers/SerialBlas.h"

namespace tmdem::mechanics {

namespace {
// Touching: a gap of at most this fraction of the first sphere's radius (a deposited bed's
// contacts are exact to round-off; an imported one's overlap). At |g| h^2 (10 um at 1 ms) the
// deposited 10,000 bed took 27,115 contacts into its first step instead of 26,554, and the
// step took longer than from zero impulses.
constexpr double kTouchingGapFraction = 1e-6;

// The balance of static_warm_start (StaticWarmStart.h): rounds of the least change dr of the
// reactions, in the norm |dr_n|^2 + kTangentialWeight |dr_t|^2, after which every held mobile
// particle's momentum change H r equals -M v_free (linear and angular: the particle at rest),
// each round projected onto the cones and the next one taken over the contacts still closed.
// The weight: measured on the 160-layer shaft of bench/depth_and_load.py (one round, mean
// sweeps per step): weight 1: 706, 4: 483, 16: 450, 100: 241, 1,000: 237, 10^5: 1,071 (against
// 1,070 without the balance); on the gauntlet's tall_column no weight was safe (at 1,000 one seed
// took 59 steps of 5,478 mean sweeps; docs/mechanics.md "The first step").
constexpr double kTangentialWeight = 100.0;
// Each particle's six rows regularised by this fraction of their diagonal: a rattler held by one
// or two contacts cannot be balanced in every direction, and its impulses stay bounded.
constexpr double kBalanceRegularisation = 1e-6;

template <class Touching>
void balance(const ContactProblem& problem, Touching&& touching, const std::vector<char>& held, int rounds,
             std::vector<Eigen::Vector3d>& reactions) {
  const std::size_t contacts = problem.size(), n = problem.particle_count;
  // Rows: 6 per held mobile particle (momentum N s, angular momentum N s m).
  std::vector<std::int32_t> row_of(n, -1);
  std::int32_t rows = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (held[i] && problem.inverse_mass[i] > 0.0) {
      row_of[i] = rows;
      rows += 6;
    }
  if (rows == 0) return;
  std::vector<char> in_set(contacts, 0);
  for (std::size_t c = 0; c < contacts; ++c) in_set[c] = touching(c);
  const Eigen::Vector3d inverse_weight(1.0, 1.0 / kTangentialWeight, 1.0 / kTangentialWeight);
  // H_c for each side that is a held mobile particle: its momentum change per unit local impulse
  // (ContactKinematics.h's columns at unit mass and inertia); a wall side has no rows.
  const auto sides = [&](std::size_t c, Eigen::Matrix<double, 6, 3> (&h)[2], std::int32_t (&row)[2]) {
    const ContactColumns columns = contact_columns(problem, c);
    const std::int32_t j = problem.body_j[c];
    row[0] = row_of[std::size_t(problem.body_i[c])];
    row[1] = is_wall(j) ? -1 : row_of[std::size_t(j)];
    for (int side = 0; side < 2; ++side) {
      h[side].topRows<3>() = columns.linear[side];
      h[side].bottomRows<3>() = columns.angular[side];
    }
  };
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd imbalance(rows), lambda;
  Eigen::SparseMatrix<double> matrix(rows, rows);
  // CHOLMOD's supernodal Cholesky, as the interior point's (Eigen's simplicial LDL^T took about 3 s
  // a round on the 160-layer shaft), the BLAS held to one thread: the same bits for any count.
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> factor;
  const SerialBlas serial_blas;
  for (int round = 0; round < rounds; ++round) {
    if (round > 0)
      for (std::size_t c = 0; c < contacts; ++c) in_set[c] = in_set[c] && reactions[c][0] > 0.0;
    // imbalance = -M v_free - H r over the set; matrix = H D^-1 H^T.
    for (std::size_t i = 0; i < n; ++i) {
      if (row_of[i] < 0) continue;
      const double inertia = problem.inverse_inertia[i] > 0.0 ? 1.0 / problem.inverse_inertia[i] : 0.0;
      imbalance.segment<3>(row_of[i]) = -problem.free_velocity[i] / problem.inverse_mass[i];
      imbalance.segment<3>(row_of[i] + 3) = -inertia * problem.free_angular_velocity[i];
    }
    triplets.clear();
    // Every diagonal entry present (a row no contact reaches, or a zero block entry, would
    // otherwise be inserted below, moving the whole matrix: a fifth of deep_steel's run, perf).
    for (std::int32_t k = 0; k < rows; ++k) triplets.emplace_back(k, k, 0.0);
    for (std::size_t c = 0; c < contacts; ++c) {
      if (!in_set[c]) continue;
      Eigen::Matrix<double, 6, 3> h[2];
      std::int32_t row[2];
      sides(c, h, row);
      for (int a = 0; a < 2; ++a) {
        if (row[a] < 0) continue;
        imbalance.segment<6>(row[a]) -= h[a] * reactions[c];
        for (int b = 0; b < 2; ++b) {
          if (row[b] < 0) continue;
          const Eigen::Matrix<double, 6, 6> block = h[a] * inverse_weight.asDiagonal() * h[b].transpose();
          for (int x = 0; x < 6; ++x)
            for (int y = 0; y < 6; ++y)
              if (block(x, y) != 0.0) triplets.emplace_back(row[a] + x, row[b] + y, block(x, y));
        }
      }
    }
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    double largest = 0.0;
    for (int k = 0; k < rows; ++k) largest = std::max(largest, matrix.coeff(k, k));
    if (!(largest > 0.0)) return;
    for (int k = 0; k < rows; ++k) {
      double& diagonal = matrix.coeffRef(k, k);
      diagonal += kBalanceRegularisation * std::max(diagonal, 1e-12 * largest);
    }
    factor.compute(matrix);
    if (factor.info() != Eigen::Success) return;  // the vertical start stands
    lambda = factor.solve(imbalance);
    for (std::size_t c = 0; c < contacts; ++c) {
      if (!in_set[c]) continue;
      Eigen::Matrix<double, 6, 3> h[2];
      std::int32_t row[2];
      sides(c, h, row);
      Eigen::Vector3d change = Eigen::Vector3d::Zero();
      for (int a = 0; a < 2; ++a)
        if (row[a] >= 0) change += h[a].transpose() * lambda.segment<6>(row[a]);
      Eigen::Vector3d next = reactions[c] + inverse_weight.cwiseProduct(change);
      if (problem.dimension == 2) next[2] = 0.0;
      reactions[c] = project_onto_coulomb_cone(next, problem.mu[c]);  // scales r_t: a 2D one stays in plane
    }
  }
}

}  // namespace

void static_warm_start(const ContactProblem& problem, const std::vector<double>& gap_m,
                       const std::vector<Eigen::Vector3d>& positions_m,
                       const Eigen::Vector3d& gravity_m_per_s2, double h_s,
                       std::vector<Eigen::Vector3d>& reactions, int balance_rounds) {
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
  if (balance_rounds > 0) balance(problem, touching, held, balance_rounds, reactions);
}

}  // namespace tmdem::mechanics
