#include "thermal/steady/SteadyStateSolver.h"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>

#include "thermal/integrators/BoomerAmgPreconditioner.h"
#include "thermal/integrators/SundialsContext.h"
#include "thermal/integrators/SundialsHandles.h"

namespace tmdem::thermal {
namespace {

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// 1 for the nodes Newton solves for: free and in a component that exchanges heat with a held
// particle or with the outside (a wall, a fluid, a source's... any non-zero Laplacian row sum).
std::vector<std::uint8_t> solved_nodes(const ThermalSystem& system, const JacobianEvaluation& J) {
  const auto& net = system.network();
  const std::size_t n = system.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  // Column sums: a conservative exchange (also the one-sided pair radiation, whose rows do not
  // sum to zero away from equal temperatures) adds up to zero down each column.
  std::vector<double> row_sum(J.diagonal_W_per_K), row_abs(n, 0.0);
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    const double h_ab = J.edge_W_per_K[e] + J.edge_ab_W_per_K[e];  // d q_a / d T_b: column b
    const double h_ba = J.edge_W_per_K[e] + J.edge_ba_W_per_K[e];  // d q_b / d T_a: column a
    if (h_ab == 0.0 && h_ba == 0.0) continue;
    const auto a = std::size_t(net.edge_a[e]), b = std::size_t(net.edge_b[e]);
    parent[find_root(parent, a)] = find_root(parent, b);
    row_sum[a] += h_ba;
    row_sum[b] += h_ab;
    row_abs[a] += std::abs(h_ba);
    row_abs[b] += std::abs(h_ab);
  }
  std::vector<std::uint8_t> anchored_root(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    // A pure Laplacian row sums to zero up to the round-off of adding its entries.
    const bool exchanges_outside = std::abs(row_sum[i]) > 1e-12 * row_abs[i] &&
                                   J.diagonal_W_per_K[i] != 0.0;
    if (net.held[i] || exchanges_outside) anchored_root[find_root(parent, i)] = 1;
  }
  std::vector<std::uint8_t> solved(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    solved[i] = !net.held[i] && anchored_root[find_root(parent, i)];
  return solved;
}

}  // namespace

SteadyState solve_steady_state(const ThermalSystem& system, std::span<const double> T0_K,
                               const SteadyStateOptions& options) {
  const auto& net = system.network();
  const auto& pattern = system.pattern();
  const std::size_t n = system.size();
  if (T0_K.size() != n)
    throw ThermalSolverError("steady state: " + std::to_string(T0_K.size()) +
                             " starting temperatures for " + std::to_string(n) + " particles");
  SteadyState out;
  out.T_K.assign(T0_K.begin(), T0_K.end());
  if (n == 0) return out;

  JacobianEvaluation J;
  system.evaluate_jacobian(out.T_K, J);
  const auto solved = solved_nodes(system, J);
  out.floating.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    out.floating[i] = !net.held[i] && !solved[i];
    out.floating_particles += out.floating[i];
  }

  const bool amg = options.linear_solver == LinearSolverKind::Amg;
  if (amg && !system.symmetric_jacobian())
    throw ThermalSolverError(
        "steady state: linear_solver \"amg\" needs a symmetric Jacobian, but temperature-"
        "dependent properties or pair radiation make it one-sided; use \"klu\"");
  SundialsContext ctx;
  auto x = make_serial_vector(sunindextype(n), ctx, "steady-state correction");
  auto b = make_serial_vector(sunindextype(n), ctx, "steady-state residual");
  auto A = checked_sundials_object<MatrixPtr>(
      SUNSparseMatrix(sunindextype(n), sunindextype(n), sunindextype(pattern.nonzeros()), CSC_MAT,
                      ctx),
      "SUNSparseMatrix");
  LinearSolverPtr LS;
  std::unique_ptr<BoomerAmgPreconditioner> multigrid;
  if (amg) {
    multigrid = std::make_unique<BoomerAmgPreconditioner>();
    multigrid->analyse(pattern);
  } else {
    LS = checked_sundials_object<LinearSolverPtr>(SUNLinSol_KLU(x.get(), A.get(), ctx),
                                                  "SUNLinSol_KLU");
    // Symmetric pattern: AMD ordering (as the integrators use).
    if (SUNLinSol_KLUSetOrdering(LS.get(), 0) != 0)
      throw ThermalSolverError("SUNLinSol_KLUSetOrdering failed");
    if (const int flag = SUNLinSolInitialize(LS.get()); flag != 0)
      throw ThermalSolverError("SUNLinSolInitialize (KLU) failed", flag);
  }
  std::vector<double> zero_shift(amg ? n : 0, 0.0);

  std::vector<double> q(n);
  double* values = SM_DATA_S(A.get());
  double* rhs = N_VGetArrayPointer(b.get());
  double* dT = N_VGetArrayPointer(x.get());
  double boundary_W = 0.0, previous_dT = 0.0;
  std::vector<double> factored_values;
  for (int it = 1; it <= options.max_newton_iterations; ++it) {
    if (!system.heat_flow(out.T_K, q, boundary_W))
      throw ThermalSolverError("steady state: a heat-transfer mode refused the temperatures of "
                               "Newton iteration " + std::to_string(it) + " (outside its domain)");
    if (it > 1) system.evaluate_jacobian(out.T_K, J);
    // d q / d T of the solved nodes; every other row is the identity with a zero right-hand side.
    std::copy(pattern.column_start.begin(), pattern.column_start.end(), SM_INDEXPTRS_S(A.get()));
    std::copy(pattern.row_index.begin(), pattern.row_index.end(), SM_INDEXVALS_S(A.get()));
    std::fill(values, values + pattern.nonzeros(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      values[pattern.diagonal_slot[i]] = solved[i] ? J.diagonal_W_per_K[i] : 1.0;
      rhs[i] = solved[i] ? -q[i] : 0.0;
    }
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      const auto a = net.edge_a[e], bb = net.edge_b[e];
      if (!solved[a] || !solved[bb]) continue;
      values[pattern.slot_ab[e]] += J.edge_W_per_K[e] + J.edge_ab_W_per_K[e];
      values[pattern.slot_ba[e]] += J.edge_W_per_K[e] + J.edge_ba_W_per_K[e];
    }
    if (amg) {
      // CG needs a positive definite matrix: -J on the solved block (a Laplacian with a sink),
      // the identity elsewhere (its rows are 1 already), and q as the right-hand side.
      for (std::size_t i = 0; i < n; ++i) {
        if (!solved[i]) continue;
        rhs[i] = -rhs[i];
        for (auto s = pattern.column_start[i]; s < pattern.column_start[i + 1]; ++s)
          values[s] = -values[s];
      }
    }
    // A linear network (or a converged nonlinear one) gives the same matrix again: keep its
    // factors. The factorisation is nearly all the cost (a 40^3 lattice: ~70 s for KLU).
    const bool same_matrix = it > 1 && std::equal(values, values + pattern.nonzeros(),
                                                  factored_values.begin());
    if (!same_matrix) {
      if (amg) {
        if (!multigrid->factor({values, pattern.nonzeros()}, 1.0, zero_shift))
          throw ThermalSolverError("steady state: BoomerAMG could not set up its hierarchy "
                                   "(Newton iteration " + std::to_string(it) + ")");
      } else if (const int flag = SUNLinSolSetup(LS.get(), A.get()); flag != 0) {
        throw ThermalSolverError("steady state: KLU could not factorise the conductance matrix "
                                 "(flag " + std::to_string(flag) + ", Newton iteration " +
                                 std::to_string(it) + "): singular or ill-conditioned", flag);
      }
      factored_values.assign(values, values + pattern.nonzeros());
      ++out.factorizations;
    }
    if (amg) {
      std::fill(dT, dT + n, 0.0);
      const auto cg = multigrid->solve_cg({rhs, n}, {dT, n}, options.cg_tolerance,
                                          options.max_cg_iterations);
      out.cg_iterations += cg.iterations;
      if (!cg.converged)
        throw ThermalSolverError(
            "steady state: conjugate gradients with BoomerAMG did not reach the relative "
            "residual " + std::to_string(options.cg_tolerance) + " in " +
            std::to_string(cg.iterations) + " iterations (reached " +
            std::to_string(cg.relative_residual) + ", Newton iteration " + std::to_string(it) + ")");
    } else if (const int flag = SUNLinSolSolve(LS.get(), A.get(), x.get(), b.get(), 0.0); flag != 0) {
      throw ThermalSolverError("steady state: KLU solve failed (flag " + std::to_string(flag) +
                               ", Newton iteration " + std::to_string(it) + ")", flag);
    }
    double max_dT = 0.0, max_T = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(dT[i]))
        throw ThermalSolverError("steady state: non-finite Newton correction at particle " +
                                 std::to_string(i) + " (iteration " + std::to_string(it) + ")");
      out.T_K[i] += dT[i];
      max_dT = std::max(max_dT, std::abs(dT[i]));
      max_T = std::max(max_T, std::abs(out.T_K[i]));
    }
    out.newton_iterations = it;
    out.max_correction_K = max_dT;
    // Converged, or stuck at the round-off floor of an ill-conditioned matrix (the correction
    // no longer halves while already tiny).
    const double scale = 1.0 + max_T;
    const bool stalled = it > 1 && max_dT > 0.5 * previous_dT && max_dT <= 1e-9 * scale;
    previous_dT = max_dT;
    if (max_dT <= options.relative_tolerance * scale || stalled) {
      if (!system.heat_flow(out.T_K, q, boundary_W))
        throw ThermalSolverError("steady state: a heat-transfer mode refused the converged "
                                 "temperatures (outside its domain)");
      for (std::size_t i = 0; i < n; ++i)
        if (solved[i]) out.max_residual_W = std::max(out.max_residual_W, std::abs(q[i]));
      return out;
    }
  }
  throw ThermalSolverError("steady state: Newton did not converge in " +
                           std::to_string(options.max_newton_iterations) +
                           " iterations (last correction " + std::to_string(out.max_correction_K) +
                           " K)");
}

}  // namespace tmdem::thermal
