#include "coupling/run/LinearSolverChoice.h"

namespace tmdem::coupling {

namespace {

std::size_t klu_particles(int dimension) {
  return dimension == 2 ? kKluParticles2d : kKluParticles3d;
}

}  // namespace

LinearSolverChoice choose_linear_solver(const LinearSolverProblem& p) {
  using thermal::LinearSolverKind;
  LinearSolverChoice c;
  if (p.requested) {
    c.kind = *p.requested;
    const std::string named = "thermal.linear_solver = \"" + c.name() + "\"";
    c.reason = "explicit: " + named;
    if (p.processes > 1 && c.kind != LinearSolverKind::Amg)
      c.refusal = named + " runs in one process only; use \"amg\" (conjugate gradients with "
                          "BoomerAMG across the processes)";
    return c;
  }
  c.automatic = true;
  const std::string n = std::to_string(p.particles) + " particles";
  const std::string klu_limit = std::to_string(klu_particles(p.dimension));
  const std::string dim = " in " + std::to_string(p.dimension) + "D";
  if (p.processes > 1) {
    c.kind = LinearSolverKind::Amg;
    c.reason = "auto: heating over " + std::to_string(p.processes) +
               " MPI processes, which only amg spans";
  } else if (!p.symmetric_jacobian) {
    c.kind = LinearSolverKind::Klu;
    c.reason = "auto: one-sided Jacobian (temperature-dependent properties or particle-particle "
               "radiation), which pcg and amg cannot take";
  } else if (p.particles < klu_particles(p.dimension)) {
    c.kind = LinearSolverKind::Klu;
    c.reason = "auto: " + n + " < " + klu_limit + dim;
  } else if (p.particles < kAmgParticles) {
    c.kind = LinearSolverKind::Pcg;
    c.reason = "auto: " + n + " >= " + klu_limit + dim + ", symmetric Jacobian";
  } else {
    c.kind = LinearSolverKind::Amg;
    c.reason = "auto: " + n + " >= " + std::to_string(kAmgParticles) + ", symmetric Jacobian";
  }
  return c;
}

LinearSolverChoice choose_linear_solver(const Scene& scene, const thermal::ThermalSystem& system,
                                        int processes) {
  return choose_linear_solver({scene.thermal.linear_solver, scene.particles.size(),
                               scene.dimension, processes, system.symmetric_jacobian()});
}

LinearSolverChoice choose_distributed_linear_solver(const Scene& scene, int processes) {
  // Rule 2 comes before the symmetry test, so `true` here changes nothing for processes > 1.
  return choose_linear_solver(
      {scene.thermal.linear_solver, scene.particles.size(), scene.dimension, processes, true});
}

std::string klu_size_warning(const LinearSolverProblem& p) {
  if (p.requested != thermal::LinearSolverKind::Klu || p.dimension != 3 ||
      p.particles < kKluParticles3d)
    return "";
  return "thermal.linear_solver = \"klu\" on " + std::to_string(p.particles) +
         " particles in 3D: KLU's fill on a 3D network this size makes every factorisation "
         "slow (measured 1.7-7.5 s of CPU for a 10-s run at 10,648 particles and 121 s at "
         "46,656, where pcg took under 0.4 s) and at 10^6 particles it runs out of memory; " +
         (p.symmetric_jacobian ? std::string("leave it out (\"auto\") or set \"pcg\" or \"amg\"")
                               : std::string("the Jacobian is one-sided, so only klu can take "
                                             "it: expect a long run")) +
         " (docs/integrators.md)";
}

}  // namespace tmdem::coupling
