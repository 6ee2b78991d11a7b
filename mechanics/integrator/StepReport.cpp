#include "mechanics/integrator/StepReport.h"

#include <algorithm>

namespace tmdem::mechanics {

void MechanicsStats::add(const StepReport& report) {
  ++steps;
  last_step_s = report.time_step_s;
  total_sweeps += report.sweeps;
  max_sweeps = std::max(max_sweeps, report.sweeps);
  if (!report.converged) ++unconverged_steps;
  if (report.stalled) ++stalled_steps;
  if (report.relisted) ++relisted_steps;
  if (report.fall) {
    ++fall_steps;
    if (!report.converged) ++fall_unconverged_steps;
  }
  max_penetration_m = std::max(max_penetration_m, report.max_penetration_m);
  max_siconos_residual = std::max(max_siconos_residual, report.siconos_residual);
  if (report.siconos_residual > report.tolerance) ++siconos_unconverged_steps;
  max_natural_map_residual = std::max(max_natural_map_residual, report.natural_map_residual);
  correction_sweeps += report.correction_sweeps;
  correction_potential_J += report.correction_potential_J;
  max_travel_m = std::max(max_travel_m, report.max_travel_m);
  energy_change_J += report.energy_change_J;
  contact_dissipation_J += report.contact_dissipation_J;
  numerical_dissipation_J += report.numerical_dissipation_J;
  detection_s += report.detection_s;
  solve_s += report.solve_s;
  correction_s += report.correction_s;
  fallback += report.fallback;
}

StepReport merged(const StepReport& first, const StepReport& second) {
  StepReport m = second;
  m.sweeps = first.sweeps + second.sweeps;
  m.residual = std::max(first.residual, second.residual);
  m.converged = first.converged && second.converged;
  // The tolerance an unconverged part missed (the tightest, if both did): a step retaken in parts
  // across the schedule's change (a part at 1e-5, the later ones at the fall's 1e-4) otherwise
  // reported its failure against the last part's tolerance, its residual below it
  // (thermal_cycling: "Siconos' residual 9.97e-05, tolerance 0.0001", unconverged).
  if (!first.converged && !second.converged)
    m.tolerance = std::min(first.tolerance, second.tolerance);
  else if (!first.converged)
    m.tolerance = first.tolerance;
  m.siconos_residual = std::max(first.siconos_residual, second.siconos_residual);
  m.natural_map_residual = std::max(first.natural_map_residual, second.natural_map_residual);
  m.fall = first.fall || second.fall;
  m.stalled = first.stalled || second.stalled;
  m.correction_sweeps = first.correction_sweeps + second.correction_sweeps;
  m.correction_potential_J = first.correction_potential_J + second.correction_potential_J;
  m.max_penetration_m = std::max(first.max_penetration_m, second.max_penetration_m);
  m.max_travel_m = first.max_travel_m + second.max_travel_m;  // a bound on the whole step's
  m.rebuilt_candidates = first.rebuilt_candidates || second.rebuilt_candidates;
  m.relisted = first.relisted || second.relisted;
  m.energy_change_J = first.energy_change_J + second.energy_change_J;
  m.contact_dissipation_J = first.contact_dissipation_J + second.contact_dissipation_J;
  m.numerical_dissipation_J = first.numerical_dissipation_J + second.numerical_dissipation_J;
  m.detection_s = first.detection_s + second.detection_s;
  m.solve_s = first.solve_s + second.solve_s;
  m.correction_s = first.correction_s + second.correction_s;
  m.fallback = first.fallback;
  m.fallback += second.fallback;
  return m;
}

}  // namespace tmdem::mechanics
