#include "coupling/bridge/ThermalDiagnostics.h"

#include <algorithm>
#include <limits>
#include <numbers>
#include <vector>

#include "mechanics/model/PairIndex.h"

namespace tmdem::coupling {

ThermalDiagnostics diagnose(const Scene& scene, const ContactList& contacts,
                            const thermal::ThermalSystem& system, double max_temperature_K) {
  ThermalDiagnostics d;
  const std::size_t n = scene.particles.size();
  std::vector<double> sum_H(n, 0.0);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const double H = contacts.conductance_W_per_K[c];
    if (!(H > 0.0)) continue;
    ++d.heat_carrying_contacts;
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    for (auto id : {i, j}) {
      if (mechanics::is_wall(id)) continue;
      sum_H[std::size_t(id)] += H;
      const auto& p = scene.particles[std::size_t(id)];
      const double k = scene.materials[std::size_t(p.material)].conductivity_W_per_mK;
      const double biot = H / (k * std::numbers::pi * p.radius_m);
      if (biot > d.max_biot) {
        d.max_biot = biot;
        d.max_biot_particle = id;
      }
    }
  }
  const auto& C = system.network().heat_capacity_J_per_K;
  d.min_time_constant_s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    if (sum_H[i] > 0.0) {
      const double tau = C[i] / sum_H[i];
      d.min_time_constant_s = std::min(d.min_time_constant_s, tau);
      d.max_time_constant_s = std::max(d.max_time_constant_s, tau);
    } else {
      ++d.isolated_particles;
    }
  }
  if (d.max_time_constant_s == 0.0) d.min_time_constant_s = 0.0;
  d.explicit_bound_s = system.explicit_stability_bound_s(max_temperature_K);
  return d;
}

void print_diagnostics(std::ostream& out, const ThermalDiagnostics& d) {
  out << "thermal: " << d.heat_carrying_contacts << " heat-carrying contacts, "
      << d.isolated_particles << " particles without contact conductance\n";
  out << "thermal: largest contact Biot number Bi = H/(k pi r) = " << d.max_biot;
  if (d.max_biot_particle >= 0) out << " (particle " << d.max_biot_particle << ")";
  out << "\n";
  if (d.max_time_constant_s > 0.0)
    out << "thermal: time constants C_i / sum_j H_ij from " << d.min_time_constant_s << " s to "
        << d.max_time_constant_s << " s (stiffness ratio "
        << d.max_time_constant_s / d.min_time_constant_s << ")\n";
  out << "thermal: explicit stability bound 2/lambda_max = " << d.explicit_bound_s << " s\n";
  if (d.max_biot > 0.1)
    out << "warning: contact Biot number " << d.max_biot
        << " exceeds 0.1: the lumped (one temperature per particle) model is doubtful here\n";
}

}  // namespace tmdem::coupling
