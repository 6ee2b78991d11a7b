// CoupledRun's summary (CoupledRun.h describes the run; the fields: docs/summary.md): where the
// wall time went, the mechanics' and the thermal side's figures, the energy balances.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <omp.h>

#include "coupling/run/CoupledRunLoop.h"
#include "coupling/scene/HeatModes.h"
#include "thermal/integrators/IntegratorKind.h"

namespace tmdem::coupling::run_detail {

void CoupledRun::fill_summary() {
  summary_.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  summary_.particles = std::int64_t(scene_.particles.size());
  summary_.packing_held = scene_.effects.mechanics == MechanicsMode::Off;
  WallTimeParts parts;
  parts.mechanics_s = mechanics_seconds_;
  parts.thermal_s = thermal_seconds_;
  parts.output_s = output_seconds_;
  parts.other_s = std::max(0.0, summary_.wall_time_s - parts.mechanics_s - parts.thermal_s -
                                    parts.output_s);
  if (nscd_) {  // timed inside the steps, so within mechanics_s
    parts.detection_s = nscd_->stats().detection_s;
    parts.contact_solve_s = nscd_->stats().solve_s;
    parts.correction_s = nscd_->stats().correction_s;
  }
  summary_.wall_time_parts = parts;
  if (scene_.effects.mechanics == MechanicsMode::Coupled) summary_.thermo_mechanics = thermo_;
  const char* wait_policy = std::getenv("OMP_WAIT_POLICY");
  const char* spin_count = std::getenv("GOMP_SPINCOUNT");
  summary_.openmp = OpenMpSummary{omp_get_max_threads(), wait_policy ? wait_policy : "unset",
                                  spin_count ? spin_count : "unset"};
  summary_.imports.clear();
  for (const auto& i : scene_.imports)
    summary_.imports.push_back({i.file, std::int64_t(i.count), i.largest_overlap, i.overlap_tolerance});
  if (nscd_) {
    const auto& ms = nscd_->stats();
    summary_.mechanics.steps = ms.steps;
    summary_.mechanics.mean_iterations = ms.mean_sweeps();
    summary_.mechanics.max_iterations = ms.max_sweeps;
    summary_.mechanics.unconverged_steps = ms.unconverged_steps;
    summary_.mechanics.max_penetration_m = ms.max_penetration_m;
    summary_.mechanics.stalled_steps = ms.stalled_steps;
    summary_.mechanics.correction_sweeps = ms.correction_sweeps;
    summary_.mechanics.halved_steps = ms.halved_steps;
    summary_.mechanics.landing_halved_steps = ms.landing_halved_steps;
    summary_.mechanics.retried_steps = ms.retried_steps;
    summary_.mechanics.discarded_sweeps = ms.discarded_sweeps;
    summary_.mechanics.kept_parts_steps = ms.kept_parts_steps;
    summary_.mechanics.relisted_steps = ms.relisted_steps;
    summary_.mechanics.piston_corrections = ms.piston_corrections;
    summary_.mechanics.max_step_travel_m = ms.max_travel_m;
    summary_.mechanics.max_siconos_residual = ms.max_siconos_residual;
    summary_.mechanics.siconos_unconverged_steps = ms.siconos_unconverged_steps;
    summary_.mechanics.max_natural_map_residual = ms.max_natural_map_residual;
    summary_.mechanics.unconverged_time_steps = ms.unconverged_time_steps;
    if (nscd_->solver().has_fallback()) {
      const auto& f = ms.fallback;
      summary_.mechanics.fallback = FallbackSummary{f.solves, f.converged_by_second, f.converged_by_first_again,
                                                    f.converged_by_sweeps, f.within_when_handed_on, f.sweeps,
                                                    f.seconds, f.first_sweeps, f.first_seconds};
    }
    if (nscd_->tolerance_schedule().enabled()) {
      ToleranceScheduleSummary ts;
      ts.tolerance = scene_.mechanics.tolerance;
      // In force: the fall speed may be automatic, the fall tolerance no tighter than tolerance.
      ts.fall_tolerance = nscd_->tolerance_schedule().fall_tolerance();
      ts.fall_speed_m_s = nscd_->tolerance_schedule().fall_speed_m_per_s();
      ts.fall_share = scene_.mechanics.fall_share;
      // In force at the end (automatic: it follows the load): the smallest over the pistons.
      ts.compaction_speed_m_s = 0.0;
      for (std::size_t w = 0; w < nscd_->walls().size(); ++w) {
        const double v = nscd_->compaction_speed_m_per_s(w, scene_.mechanics.time_step_s);
        if (v > 0.0 && (ts.compaction_speed_m_s == 0.0 || v < ts.compaction_speed_m_s))
          ts.compaction_speed_m_s = v;
      }
      ts.fall_steps = ms.fall_steps;
      ts.fall_unconverged_steps = ms.fall_unconverged_steps;
      ts.collapse_steps = ms.collapse_steps;
      ts.tighten_steps = scene_.mechanics.tighten_steps;
      const std::int64_t landed = nscd_->tolerance_schedule().landed_step();
      ts.tightened = landed > 0;
      ts.tightened_step = landed;
      // Every step but a dynamic run's last is time_step long.
      ts.tightened_time_s = landed > 0 ? double(landed - 1) * scene_.mechanics.time_step_s : 0.0;
      summary_.mechanics.tolerance_schedule = ts;
    }
    // Settle runs too (their settle phase); heat is handed over by dynamic runs only.
    MechanicalEnergySummary m;
    m.energy_change_J = ms.energy_change_J;
    m.contact_dissipation_J = ms.contact_dissipation_J;
    m.numerical_dissipation_J = ms.numerical_dissipation_J;
    m.correction_potential_J = ms.correction_potential_J;
    m.heat_generated_J = contact_heat_J_;
    m.heat_share_J = dissipation_share_J_;
    m.heat_received_J =
        dissipation_received0_J_ + (integrator_ ? integrator_->dissipation_heat_J() : 0.0);
    summary_.energy.mechanical =
        m.with_errors(!frozen_ && contacts_dissipate_heat(scene_.effects));
  }
  summary_.thermal.integrator = scene_.thermal.integrator;
  const bool explicit_update =
      thermal::parse_integrator_kind(scene_.thermal.integrator) == thermal::IntegratorKind::Explicit;
  // The resolved solver; none when the run failed before its thermal side was set up.
  if (!explicit_update && linear_solver_) {
    summary_.thermal.linear_solver = linear_solver_->name();
    summary_.thermal.linear_solver_reason = linear_solver_->reason;
  }
  if (integrator_) {
    const auto st = integrator_->stats();
    summary_.thermal.steps = st.steps;
    summary_.thermal.rhs_evals = st.rhs_evals;
    summary_.thermal.jacobian_evals = st.jacobian_evals;
    summary_.thermal.linear_setups = st.linear_setups;
    summary_.thermal.error_test_failures = st.error_test_failures;
    summary_.thermal.convergence_failures = st.convergence_failures;
    summary_.thermal.reinitializations = st.reinitializations;
    summary_.thermal.wall_time_s = thermal_seconds_;
    // A coupled run re-initialises at every coupling whatever thermal.coupling says
    // (CoupledRunThermoMechanics.cpp): the summary names what was done.
    if (!frozen_)
      summary_.thermal.coupling =
          scene_.effects.mechanics == MechanicsMode::Coupled ? "restart" : scene_.thermal.coupling;
    summary_.simulated_time_s = integrator_->time_s();
    summary_.energy.initial_J = initial_energy_J_;
    summary_.energy.final_J = system_->thermal_energy_J(integrator_->temperatures_K());
    summary_.energy.boundary_heat_J = integrator_->boundary_heat_J();
    summary_.energy.balance_error_rel = RunSummary::balance_error_rel(
        summary_.energy.initial_J, summary_.energy.final_J, summary_.energy.boundary_heat_J);
  }
}

}  // namespace tmdem::coupling::run_detail
