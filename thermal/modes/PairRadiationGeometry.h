#pragma once
// What radiation between particles (ParticleRadiationMode.cpp) and radiation to the ambient
// (RadiationMode.cpp) share: which network edges radiate, the view factor of a neighbour, and the
// two [radiation] keys that switch pair radiation on and bound its reach. The ambient mode needs
// them because the share of a particle's radiation that meets its radiating neighbours does not
// also leave to the surroundings (docs/heat-modes.md "Radiation between particles").
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "thermal/modes/ModeDescription.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

inline constexpr double kStefanBoltzmann_W_per_m2K4 = 5.670374419e-8;

// Share of isotropic radiation from a point at distance d that meets a sphere of radius r.
inline double point_view_factor(double r_m, double d_m) {
  const double s = std::min(r_m / d_m, 1.0);
  return 0.5 * (1.0 - std::sqrt(1.0 - s * s));
}

// Edge e exchanges radiation: its gap is at most `reach` times the smaller radius and both
// surfaces emit.
inline bool radiating_pair(const ThermalNetwork& net, std::size_t e, double reach) {
  const auto a = net.edge_a[e], b = net.edge_b[e];
  return net.edge_gap_m[e] <= reach * std::min(net.radius_m[a], net.radius_m[b]) &&
         net.emissivity[a] > 0.0 && net.emissivity[b] > 0.0;
}

// Centre-to-centre distance of edge e, m.
inline double pair_distance_m(const ThermalNetwork& net, std::size_t e) {
  return net.radius_m[net.edge_a[e]] + net.radius_m[net.edge_b[e]] + net.edge_gap_m[e];
}

inline ModeParameter between_particles_parameter() {
  return {.key = "between_particles",
          .default_value = 0.0,
          .range = ParameterRange::any(),
          .description = "also exchange radiation between neighbouring particles (view factor of "
                         "a sphere seen from its neighbour's centre); the share of a particle's "
                         "radiation that meets them no longer reaches the surroundings",
          .boolean = true};
}

inline ModeParameter pair_cutoff_parameter() {
  return {.key = "pair_cutoff",
          .unit = "",
          .default_value = 0.5,
          .range = ParameterRange::open_closed(0.0, 2.0),
          .description = "largest gap of a radiating pair, as a fraction of the smaller radius "
                         "(no shadowing: keep it small)"};
}

}  // namespace tmdem::thermal
