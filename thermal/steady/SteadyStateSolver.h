#pragma once
// The steady state of a thermal system, q(T) = 0 for every free particle (held particles keep
// their temperature), solved directly: Newton on the heat flow with the exact mode Jacobian,
// each linear system factorised by KLU (sparse direct, through SUNDIALS). For the linear modes
// (contact and wall conduction, convection, sources) the first Newton step is the answer to
// round-off; the second only confirms it. No time stepping.
//
// A group of free particles that exchanges heat with nothing outside itself (a rattler, a pair
// touching only each other) has no determined steady temperature: its rows of the Laplacian
// are singular. Such groups are found first (connected components of the edges, anchored by a
// held particle or a node that exchanges heat with the outside) and kept at their starting
// temperature; the result counts them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "thermal/integrators/IntegratorKind.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::thermal {

struct SteadyStateOptions {
  int max_newton_iterations = 50;
  // Converged when the largest Newton correction is at most this times (1 K + max |T|), or
  // when it stalls below 1e-9 times that (round-off of an ill-conditioned matrix).
  double relative_tolerance = 1e-13;
  // Klu (and Pcg): each Newton system factorised by KLU. Amg: solved by hypre's conjugate
  // gradients with a BoomerAMG V-cycle (BoomerAmgPreconditioner.h) to cg_tolerance; Newton's
  // next step corrects what CG left (iterative refinement), so the answer is the same to the
  // Newton tolerance, in memory linear in the bed instead of KLU's fill-in. Needs a symmetric
  // Jacobian (no temperature-dependent properties, no pair radiation).
  LinearSolverKind linear_solver = LinearSolverKind::Klu;
  double cg_tolerance = 1e-12;  // relative residual of each CG solve
  int max_cg_iterations = 1000;
};

struct SteadyState {
  std::vector<double> T_K;
  int newton_iterations = 0;
  int factorizations = 0;          // KLU factorisations or AMG setups (a linear network: 1)
  long cg_iterations = 0;          // Amg: conjugate-gradient iterations over all Newton steps
  double max_correction_K = 0.0;   // of the last Newton step
  double max_residual_W = 0.0;     // largest |q_i| over the free, anchored particles at T_K
  std::size_t floating_particles = 0;  // kept at their starting temperature (see above)
  std::vector<std::uint8_t> floating;  // per particle: 1 for those (0 for the solved and held)
};

// From the starting temperatures T0_K (held particles' values are kept). Throws
// ThermalSolverError naming the cause when KLU fails (singular or ill-conditioned matrix),
// when a mode's domain is left (e.g. T <= 0 K for radiation) or when Newton does not converge
// within max_newton_iterations (with the last correction).
SteadyState solve_steady_state(const ThermalSystem& system, std::span<const double> T0_K,
                               const SteadyStateOptions& options = {});

}  // namespace tmdem::thermal
