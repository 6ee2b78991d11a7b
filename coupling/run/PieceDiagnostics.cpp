#include "coupling/run/PieceDiagnostics.h"

#include <algorithm>
#include <limits>
#include <numbers>
#include <vector>

#include "mechanics/model/PairIndex.h"
#include "thermal/integrators/MpiWorld.h"

namespace tmdem::coupling {

ThermalDiagnostics diagnose_piece(const Scene& scene, const ContactList& contacts,
                                  std::span<const std::int32_t> particle,
                                  std::span<const double> C,
                                  const thermal::NetworkPartition& partition, int rank) {
  ThermalDiagnostics d;
  const auto owned = [&](std::int64_t k) {
    return partition.owner(particle[std::size_t(k)]) == rank;
  };
  std::vector<double> sum_H(particle.size(), 0.0);  // W/K, own particles only
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const double H = contacts.conductance_W_per_K[c];
    if (!(H > 0.0)) continue;
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    if (owned(i)) ++d.heat_carrying_contacts;  // each contact once: by its first particle's owner
    for (auto k : {i, j}) {
      if (mechanics::is_wall(k) || !owned(k)) continue;
      sum_H[std::size_t(k)] += H;
      const auto id = particle[std::size_t(k)];
      const auto& p = scene.particles[std::size_t(id)];
      const double conductivity = scene.materials[std::size_t(p.material)].conductivity_W_per_mK;
      const double biot = H / (conductivity * std::numbers::pi * p.radius_m);
      if (biot > d.max_biot || (biot == d.max_biot && id < d.max_biot_particle)) {
        d.max_biot = biot;
        d.max_biot_particle = id;
      }
    }
  }
  d.min_time_constant_s = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particle.size(); ++k) {
    if (!owned(std::int64_t(k))) continue;
    if (sum_H[k] > 0.0) {
      const double tau_s = C[k] / sum_H[k];
      d.min_time_constant_s = std::min(d.min_time_constant_s, tau_s);
      d.max_time_constant_s = std::max(d.max_time_constant_s, tau_s);
    } else {
      ++d.isolated_particles;
    }
  }
  return d;
}

ThermalDiagnostics combine_shares(std::span<const ThermalDiagnostics> shares) {
  ThermalDiagnostics d;
  d.min_time_constant_s = std::numeric_limits<double>::infinity();
  d.explicit_bound_s = std::numeric_limits<double>::infinity();
  for (const auto& s : shares) {
    d.heat_carrying_contacts += s.heat_carrying_contacts;
    d.isolated_particles += s.isolated_particles;
    if (s.max_biot > d.max_biot ||
        (s.max_biot == d.max_biot && s.max_biot_particle >= 0 &&
         (d.max_biot_particle < 0 || s.max_biot_particle < d.max_biot_particle))) {
      d.max_biot = s.max_biot;
      d.max_biot_particle = s.max_biot_particle;
    }
    d.min_time_constant_s = std::min(d.min_time_constant_s, s.min_time_constant_s);
    d.max_time_constant_s = std::max(d.max_time_constant_s, s.max_time_constant_s);
    d.explicit_bound_s = std::min(d.explicit_bound_s, s.explicit_bound_s);
  }
  if (d.max_time_constant_s == 0.0) d.min_time_constant_s = 0.0;  // as diagnose: none
  return d;
}

ThermalDiagnostics combine_over_processes(const ThermalDiagnostics& mine) {
  // Seven figures a process, as doubles (the counts are exact below 2^53).
  constexpr int kFigures = 7;
  const int processes = thermal::MpiWorld::size();
  const double packed[kFigures] = {mine.max_biot,
                                   double(mine.max_biot_particle),
                                   mine.min_time_constant_s,
                                   mine.max_time_constant_s,
                                   mine.explicit_bound_s,
                                   double(mine.isolated_particles),
                                   double(mine.heat_carrying_contacts)};
  std::vector<double> all(std::size_t(kFigures * processes));
  std::vector<int> counts(std::size_t(processes), kFigures), displacements(counts.size());
  for (int r = 0; r < processes; ++r) displacements[std::size_t(r)] = kFigures * r;
  thermal::MpiWorld::all_gather(packed, all, counts, displacements);
  std::vector<ThermalDiagnostics> shares(static_cast<std::size_t>(processes));
  for (int r = 0; r < processes; ++r) {
    const double* f = &all[std::size_t(kFigures * r)];
    auto& s = shares[std::size_t(r)];
    s.max_biot = f[0];
    s.max_biot_particle = std::int64_t(f[1]);
    s.min_time_constant_s = f[2];
    s.max_time_constant_s = f[3];
    s.explicit_bound_s = f[4];
    s.isolated_particles = std::size_t(f[5]);
    s.heat_carrying_contacts = std::size_t(f[6]);
  }
  return combine_shares(shares);
}

}  // namespace tmdem::coupling
