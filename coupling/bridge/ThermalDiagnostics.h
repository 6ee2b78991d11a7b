#pragma once
// Figures that tell whether the lumped model holds and how stiff the thermal problem is:
// the largest contact Biot number Bi = H / (k pi r) (lumped temperatures are doubtful above 0.1),
// the extreme thermal time constants C_i / sum_j H_ij, and the explicit stability bound.
#include <ostream>
#include <string>

#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

struct ThermalDiagnostics {
  double max_biot = 0.0;
  std::int64_t max_biot_particle = -1;
  double min_time_constant_s = 0.0;    // over particles with at least one conductance
  double max_time_constant_s = 0.0;
  double explicit_bound_s = 0.0;       // 2 / lambda_max (Gershgorin)
  std::size_t isolated_particles = 0;  // no contact conductance
  std::size_t heat_carrying_contacts = 0;
};

ThermalDiagnostics diagnose(const Scene& scene, const ContactList& contacts,
                            const thermal::ThermalSystem& system, double max_temperature_K);
// Human-readable report; a warning line when the Biot number exceeds 0.1.
void print_diagnostics(std::ostream& out, const ThermalDiagnostics& d);

}  // namespace tmdem::coupling
