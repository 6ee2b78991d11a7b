#include "mechanics/integrator/StepReport.h"

#include <algorithm>

namespace tmdem::mechanics {

void MechanicsStats::add(const StepReport& report) {
  ++steps;
  total_sweeps += report.sweeps;
  max_sweeps = std::max(max_sweeps, report.sweeps);
  if (!report.converged) ++unconverged_steps;
  if (report.stalled) ++stalled_steps;
  if (report.fall) {
    ++fall_steps;
    if (!report.converged) ++fall_unconverged_steps;
  }
  max_penetration_m = std::max(max_penetration_m, report.max_penetration_m);
  max_siconos_residual = std::max(max_siconos_residual, report.siconos_residual);
  if (report.siconos_residual > report.tolerance) ++siconos_unconverged_steps;
  correction_sweeps += report.correction_sweeps;
  correction_potential_J += report.correction_potential_J;
  max_travel_m = std::max(max_travel_m, report.max_travel_m);
  energy_change_J += report.energy_change_J;
  contact_dissipation_J += report.contact_dissipation_J;
  numerical_dissipation_J += report.numerical_dissipation_J;
  detection_s += report.detection_s;
  solve_s += report.solve_s;
  correction_s += report.correction_s;
}

}  // namespace tmdem::mechanics
