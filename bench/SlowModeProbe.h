#pragma once
// Where plain Gauss-Seidel ("nlgs") is slow on one contact problem (bench_pour,
// TMDEM_POUR_PROBE_STEP): the problem is re-solved from zero reactions with the same
// symmetric sweeps, and after `sweeps` sweeps the probe prints the measured contraction per
// sweep of the residual and the contacts that carry the last sweep pair's change, with the
// masses of their bodies. For a heavy body H resting on a light body L on a fixed wall, the
// two normal contacts' Delassus block is [[a + b, b], [b, b]] (a = 1/m_H, b = 1/m_L) and
// Gauss-Seidel contracts their error by b / (a + b) per sweep: the probe prints that
// prediction next to each contact so the two can be compared.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <initializer_list>
#include <numeric>
#include <vector>

#include "mechanics/solvers/BlockGaussSeidelSolver.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"
#include "mechanics/solvers/NncgSolver.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::bench {

inline void print_slow_mode(const mechanics::ContactProblem& problem, int sweeps, std::FILE* out) {
  using Eigen::Vector3d;
  const std::size_t count = problem.size();
  std::vector<Vector3d> r(count, Vector3d::Zero()), m(count, Vector3d::Zero()), v, w;
  problem.velocities_from_reactions(r, v, w);
  std::vector<double> last_change(count, 0.0), residual;
  for (int sweep = 1; sweep <= sweeps; ++sweep) {
    const bool forward = sweep % 2 == 1;
    double change = 0.0, total = 0.0;
    for (std::size_t visit = 0; visit < count; ++visit) {
      const std::size_t c = forward ? visit : count - 1 - visit;
      if (!problem.solvable(c)) continue;
      const mechanics::ContactUpdate u = mechanics::gauss_seidel_visit(problem, c, 1.0, r[c], m, v, w);
      change += u.change;
      total += u.total;
      if (sweep >= sweeps - 1) last_change[c] += u.change;  // the last forward-backward pair
    }
    residual.push_back(total > 0.0 ? change / total : 0.0);
  }
  std::fprintf(out, "probe: %zu candidates, residual (change / total) by sweep:", count);
  for (int s : {1, 10, 20, 50, 100, 200, 300, 400, 500, 1000}) {
    if (s <= sweeps) std::fprintf(out, " %d:%.2e", s, residual[s - 1]);
  }
  // Contraction per sweep over the last half of the run (pairs of sweeps: the symmetric
  // sweeps alternate direction).
  const int from = sweeps / 2 - (sweeps / 2) % 2;
  if (from >= 2 && residual[from - 1] > 0.0) {
    std::fprintf(out, "\nprobe: contraction per sweep over sweeps %d-%d: %.4f\n", from, sweeps,
                 std::pow(residual[sweeps - 1] / residual[from - 1], 1.0 / (sweeps - from)));
  }
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return last_change[a] > last_change[b]; });
  const double all = std::accumulate(last_change.begin(), last_change.end(), 0.0);
  // The mass of a body, kg (0: immobile, a fixed particle or a wall).
  auto mass = [&](std::size_t body) {
    return problem.inverse_mass[body] > 0.0 ? 1.0 / problem.inverse_mass[body] : 0.0;
  };
  // The heaviest mobile neighbour of each particle through an active contact.
  std::vector<double> heaviest(problem.body_count(), 0.0);
  for (std::size_t c = 0; c < count; ++c) {
    if (r[c][0] <= 0.0 || mechanics::is_wall(problem.body_j[c])) continue;
    const std::size_t i = problem.body_i[c], j = problem.body_j[c];
    heaviest[i] = std::max(heaviest[i], mass(j));
    heaviest[j] = std::max(heaviest[j], mass(i));
  }
  // The change on contacts of a body at least 4x lighter than its heaviest neighbour (where a
  // block solve per light body acts).
  double light_share = 0.0;
  for (std::size_t c = 0; c < count; ++c) {
    for (std::size_t body : {static_cast<std::size_t>(problem.body_i[c]),
                             mechanics::is_wall(problem.body_j[c]) ? problem.wall_body(problem.body_j[c])
                                                                   : static_cast<std::size_t>(problem.body_j[c])}) {
      if (problem.inverse_mass[body] > 0.0 && heaviest[body] * problem.inverse_mass[body] >= 4.0) {
        light_share += last_change[c];
        break;
      }
    }
  }
  std::fprintf(out, "probe: share of the change on contacts of a body >= 4x lighter than its heaviest neighbour: %.3f\n",
               light_share / all);
  double top = 0.0;
  std::fprintf(out, "probe: last pair's change %.3e N s; largest contributors:\n", all);
  std::fprintf(out, "probe:   contact  m_i (kg)  m_j (kg, 0 wall)  r_n (N s)  share  "
                    "b/(a+b) of the lighter body under its heaviest neighbour\n");
  for (std::size_t k = 0; k < std::min<std::size_t>(12, count); ++k) {
    const std::size_t c = order[k];
    const std::size_t i = problem.body_i[c];
    const bool wall = mechanics::is_wall(problem.body_j[c]);
    const std::size_t j = wall ? problem.wall_body(problem.body_j[c]) : problem.body_j[c];
    const std::size_t light = wall || mass(i) <= mass(j) ? i : j;
    const double a = heaviest[light] > 0.0 ? 1.0 / heaviest[light] : 0.0, b = problem.inverse_mass[light];
    top += last_change[c];
    std::fprintf(out, "probe:   %7zu  %.3e  %.3e  %.3e  %.3f  %.4f\n", c, mass(i), mass(j), r[c][0],
                 last_change[c] / all, b / (a + b));
  }
  std::fprintf(out, "probe: the 12 largest carry %.3f of the change\n", top / all);
}

// Sweeps and CPU time of each named solver on the same problem from zero reactions, to
// tolerances 1e-4 and 1e-6 (at most 5,000 sweeps).
inline void print_solver_sweeps(const mechanics::ContactProblem& problem,
                                std::initializer_list<const char*> names, std::FILE* out) {
  for (const char* name : names) {
    for (double tolerance : {1e-4, 1e-6}) {
      mechanics::SolverSettings settings;
      settings.tolerance = tolerance;
      settings.max_iterations = 5000;
      auto solver = mechanics::make_contact_solver(name, settings);
      std::vector<Eigen::Vector3d> r(problem.size(), Eigen::Vector3d::Zero()), m = r, v, w;
      const std::clock_t start = std::clock();
      const mechanics::SolveReport report = solver->solve_with_rolling(problem, r, m, v, w);
      std::fprintf(out, "probe: %-12s tolerance %.0e: %5d sweeps, residual %.2e, converged %d, %.3f s CPU",
                   name, tolerance, report.sweeps, report.residual, report.converged ? 1 : 0,
                   static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
      if (const auto* nncg = dynamic_cast<const mechanics::NncgSolver*>(solver.get()))
        std::fprintf(out, ", %d conjugate steps, %d damped (beta > 1)", nncg->steps(), nncg->damped());
      std::fprintf(out, "\n");
    }
  }
}

// nlgs_block with other mass ratios (which bodies get a block visit), with its block counts.
inline void print_block_ratios(const mechanics::ContactProblem& problem, std::FILE* out) {
  for (double ratio : {8.0, 4.0, 2.0, 1.0}) {
    mechanics::SolverSettings settings;
    settings.tolerance = 1e-4;
    settings.max_iterations = 5000;
    mechanics::BlockGaussSeidelSolver solver(settings, ratio);
    std::vector<Eigen::Vector3d> r(problem.size(), Eigen::Vector3d::Zero()), m = r, v, w;
    const std::clock_t start = std::clock();
    const mechanics::SolveReport report = solver.solve_with_rolling(problem, r, m, v, w);
    std::fprintf(out, "probe: nlgs_block ratio %.1f: %zu blocks, %5d sweeps, converged %d, %lld block visits, %lld fallbacks, %.3f s CPU\n",
                 ratio, solver.block_count(), report.sweeps, report.converged ? 1 : 0,
                 static_cast<long long>(solver.block_visits()), static_cast<long long>(solver.block_fallbacks()),
                 static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
  }
}

}  // namespace tmdem::bench
