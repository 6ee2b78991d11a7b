#pragma once
// One interface for every thermal integrator (CVODE, IDA, explicit): the coupling advances the
// temperatures to a time and reads them back, whatever the method (MFEM's ODESolver pattern).
#include <span>
#include <string>
#include <string_view>

#include "thermal/integrators/IntegratorKind.h"

namespace tmdem::thermal {

struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;
  long jacobian_evals = 0;        // Jacobian (KLU) or preconditioner (PCG) evaluations
  long linear_setups = 0;
  long linear_iterations = 0;     // PCG iterations (0 for KLU)
  long error_test_failures = 0;
  long convergence_failures = 0;
  long reinitializations = 0;     // restarts after the contact graph changed shape, or on demand

  // Adds an earlier segment's counters (all but reinitializations).
  void add_counters(const IntegratorStats& earlier) {
    steps += earlier.steps;
    rhs_evals += earlier.rhs_evals;
    jacobian_evals += earlier.jacobian_evals;
    linear_setups += earlier.linear_setups;
    linear_iterations += earlier.linear_iterations;
    error_test_failures += earlier.error_test_failures;
    convergence_failures += earlier.convergence_failures;
  }
};

struct IntegratorSettings {
  // cvode, ida: parsed once where the name is read (the scene's thermal.linear_solver, the
  // accuracy study's --methods); "auto" is resolved by coupling before it gets here.
  LinearSolverKind linear_solver = LinearSolverKind::Klu;
  double relative_tolerance = 1.0e-6;
  double absolute_tolerance_K = 1.0e-6;
  double explicit_step_s = 0.0;        // 0: 0.9 of the stability bound
  // Upper bound of every temperature of the run (initial values, walls, fluid, surroundings):
  // the explicit stability bound of a nonlinear mode is evaluated there.
  double max_temperature_K = 0.0;
  // Step exactly to each requested time instead of stepping past it and interpolating. Needed
  // when the network changes at those times (dynamic coupling).
  bool stop_at_each_time = false;
  long max_steps_per_call = 1000000;
};

class ThermalIntegrator {
 public:
  virtual ~ThermalIntegrator() = default;
  virtual IntegratorKind kind() const = 0;
  std::string_view name() const { return name_of(kind()); }
  bool is_explicit() const { return kind() == IntegratorKind::Explicit; }

  // Starts at t0 with temperatures T0 (held particles keep theirs) and a boundary-heat counter
  // that starts at boundary_heat0 (non-zero on restart from a checkpoint).
  virtual void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J = 0.0) = 0;
  // Advances to t. Throws ThermalSolverError on failure. Detects a contact-graph shape change in
  // the system (ThermalSystem::topology_version) and re-analyses before stepping.
  virtual void advance_to(double t_s) = 0;
  // Forgets the step history and restarts from the current state (coupled-step strategy
  // "restart every mechanical step").
  virtual void restart() = 0;

  virtual double time_s() const = 0;
  virtual std::span<const double> temperatures_K() const = 0;
  // Heat that entered the free particles since t = 0 through walls, fluid, radiation, sources and
  // held particles, J, integrated with the same steps as the temperatures.
  virtual double boundary_heat_J() const = 0;
  // The part of it that the dissipation modes (friction heat) put in, J, since initialize(),
  // integrated with the same steps: what the thermal side really received of the mechanical
  // dissipation (a BDF history carried across the source's jumps receives less).
  virtual double dissipation_heat_J() const = 0;
  virtual IntegratorStats stats() const = 0;
  // Counters of earlier segments (restart from a checkpoint, or a re-initialisation at a
  // checkpoint time): after initialize(), stats() reports these plus what comes after.
  virtual void restore_stats(const IntegratorStats& earlier) = 0;
};

}  // namespace tmdem::thermal
