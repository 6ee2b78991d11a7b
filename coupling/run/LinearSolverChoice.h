#pragma once
// thermal.linear_solver = "auto" (the default) turned into the linear solver that fits the
// problem, once per run, here and nowhere else; an explicit "klu", "pcg" or "amg" is kept
// exactly. Every user of the scene's linear solver (the run, its MPI refusal, tmdem check, the
// accuracy and conductivity studies) asks this, so "auto" never reaches the thermal side.
//
// The rule, first match wins:
//   1. an explicit choice                    -> that solver; over more than one MPI process
//                                               only amg, else refused (`refusal`: the one place
//                                               this is decided; the MPI integrator is always amg)
//   2. more than one MPI process             -> amg (the only solver that spans processes)
//   3. a one-sided Jacobian (temperature-dependent properties, particle-particle radiation)
//                                            -> klu (pcg and amg need a symmetric one)
//   4. fewer particles than kKluParticles3d in 3D, kKluParticles2d in 2D -> klu
//   5. fewer than kAmgParticles              -> pcg
//   6. otherwise                             -> amg
// Why these numbers: docs/benchmarks.md "Choosing the linear solver" timed cvode on a
// simple-cubic (square in 2D) lattice, mechanics off, 10 s and 100 s, one thread, CPU seconds.
// pcg beat KLU at every size; KLU's cost grows as ~n^2 in 3D (the factor's fill-in) and gently
// in 2D: a 10-s 3D run took KLU 0.4-1.2 s at 4,913 particles (pcg 0.06-0.16 s), 1.7-7.5 s at
// 10,648, 15-60 s at 19,683 and 121 s at 46,656, and at 10^6 it ran out of memory at t = 0;
// in 2D 0.9-3.0 s at 50,176 (pcg 0.2-1.5 s) and 2.1-8.2 s at 99,856. KLU is kept below the
// sizes where it costs about a second more than pcg, since it is exact (no inner tolerance:
// the energy balance closes to round-off) and every example and test scene (2,000 particles
// at most) keeps its bits. amg against pcg: 20-50% slower on short runs, within 15% from 10^5
// to 3 x 10^5 on long stiff runs, 23% faster on the long stiff run at 10^6 (a V-cycle's
// conjugate-gradient iterations stay flat where IC(0)'s grow with the bed's width), for 1.2x
// the memory: amg where its gain is in minutes.
#include <cstddef>
#include <optional>
#include <string>

#include "coupling/scene/Scene.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

inline constexpr std::size_t kKluParticles3d = 5'000;    // 3D: klu below, pcg from here
inline constexpr std::size_t kKluParticles2d = 50'000;   // 2D: fill-in grows far slower
inline constexpr std::size_t kAmgParticles = 500'000;    // pcg below, amg from here

// What the rule looks at.
struct LinearSolverProblem {
  // thermal.linear_solver as the scene parsed it: empty for "auto".
  std::optional<thermal::LinearSolverKind> requested;
  std::size_t particles = 0;       // thermal unknowns (the whole bed, also over MPI)
  int dimension = 3;               // simulation.dimension
  int processes = 1;               // MPI processes heating the bed
  bool symmetric_jacobian = true;  // thermal::ThermalSystem::symmetric_jacobian()
};

struct LinearSolverChoice {
  thermal::LinearSolverKind kind = thermal::LinearSolverKind::Klu;
  bool automatic = false;  // chosen by "auto", not named by the scene
  // Why, for the run's report, the summary (thermal.linear_solver_reason) and tmdem check:
  // "auto: 25000 particles >= 5000 in 3D, symmetric Jacobian", "explicit: thermal.linear_solver
  // = \"klu\"".
  std::string reason;
  // Not empty when the explicit choice cannot be honoured (klu or pcg over MPI): why and what to
  // set instead, e.g. "thermal.linear_solver = \"klu\" runs in one process only; use \"amg\" ...".
  std::string refusal;
  std::string name() const { return std::string(thermal::name_of(kind)); }
};

// The rule above.
LinearSolverChoice choose_linear_solver(const LinearSolverProblem& problem);

// The rule for `scene` heated over `processes` MPI processes, the Jacobian's symmetry taken from
// `system` (the scene's thermal system: the modes it switches on and its materials).
LinearSolverChoice choose_linear_solver(const Scene& scene, const thermal::ThermalSystem& system,
                                        int processes);

// The rule where the system is not built yet and the processes decide alone (more than one:
// amg whatever the symmetry, an explicit klu or pcg refused; the MPI integrator refuses a
// one-sided Jacobian itself).
LinearSolverChoice choose_distributed_linear_solver(const Scene& scene, int processes);

// tmdem check's warning for an explicit "klu" on a 3D bed at or above kKluParticles3d (KLU's
// fill-in makes it the slowest there, and at 10^6 particles its factorisation runs out of
// memory); empty otherwise.
std::string klu_size_warning(const LinearSolverProblem& problem);

}  // namespace tmdem::coupling
