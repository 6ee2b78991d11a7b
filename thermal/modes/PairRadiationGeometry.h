#pragma once
// What radiation between particles (ParticleRadiationMode.cpp) and radiation to the ambient
// (RadiationMode.cpp) share: which network edges radiate, the view factors of a particle's
// neighbours and walls, and the [radiation] keys that shape them. The ambient mode needs them
// because what a particle's radiation meets on its neighbours and walls does not also leave to
// the surroundings (docs/heat-modes.md "Radiation to the surroundings and between particles").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "thermal/modes/ModeDescription.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

inline constexpr double kStefanBoltzmann_W_per_m2K4 = 5.670374419e-8;

// Share of isotropic radiation from a point at distance d that meets a sphere of radius r.
inline double point_view_factor(double r_m, double d_m) {
  const double s = std::min(r_m / d_m, 1.0);
  return 0.5 * (1.0 - std::sqrt(1.0 - s * s));
}

// Edge e exchanges radiation: its gap is at most `reach` times the smaller radius, both
// surfaces emit, and no third particle crosses the line between their centres.
inline bool radiating_pair(const ThermalNetwork& net, std::size_t e, double reach) {
  const auto a = net.edge_a[e], b = net.edge_b[e];
  return net.edge_gap_m[e] <= reach * std::min(net.radius_m[a], net.radius_m[b]) &&
         net.emissivity[a] > 0.0 && net.emissivity[b] > 0.0 &&
         (net.edge_shadowed.empty() || net.edge_shadowed[e] == 0);
}

// Centre-to-centre distance of edge e, m.
inline double pair_distance_m(const ThermalNetwork& net, std::size_t e) {
  return net.radius_m[net.edge_a[e]] + net.radius_m[net.edge_b[e]] + net.edge_gap_m[e];
}

// Wall edge w exchanges radiation: its gap is at most `reach` times the particle's radius and
// both surfaces emit.
inline bool radiating_wall(const ThermalNetwork& net, std::size_t w, double reach) {
  const auto i = net.wall_node[w];
  return !net.wall_emissivity.empty() && net.wall_gap_m[w] <= reach * net.radius_m[i] &&
         net.emissivity[i] > 0.0 && net.wall_emissivity[w] > 0.0;
}

// Effective emissivity of two grey surfaces facing each other.
inline double exchange_emissivity(double eps_a, double eps_b) {
  return 1.0 / (1.0 / eps_a + 1.0 / eps_b - 1.0);
}

// How each particle's emission is shared, from its radiating neighbours' view factors
// F_ij = point_view_factor(r_j, d_ij), their sum S_i and the open share o_i = max(0, 1 - S_i):
//   - each radiating wall takes half the open share (the wall fills a half-space; the
//     neighbours are taken to shade every direction alike), two or more share it all:
//     wall_share_i = o_i / max(2, n_walls);
//   - surroundings: what is left, o_i - n_walls wall_share_i, reaches the surroundings;
//   - enclosed (no surroundings): nothing leaves; every view factor of particle i is scaled by
//     pair_scale_i = 1 / (S_i + n_walls wall_share_i), so that its emission all meets its
//     neighbours and walls (a particle with none exchanges nothing).
// Computed once per geometry from the whole network; a study's copy of it with fewer wall
// edges keeps the same shares (the walls are still there, only their heat is not counted).
struct RadiationShares {
  std::vector<double> pair_scale;  // per node: scale of its pair view factors
  std::vector<double> wall_share;  // per node: view factor to each radiating wall
  std::vector<double> open_share;  // per node: share reaching the surroundings
};

inline RadiationShares radiation_shares(const ThermalNetwork& net, double reach, bool walls,
                                        bool enclosed) {
  const std::size_t n = net.node_count();
  RadiationShares s;
  s.pair_scale.assign(n, 1.0);
  s.wall_share.assign(n, 0.0);
  s.open_share.assign(n, 1.0);
  std::vector<double> seen(n, 0.0);
  std::vector<int> wall_count(n, 0);
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    if (!radiating_pair(net, e, reach)) continue;
    const auto a = net.edge_a[e], b = net.edge_b[e];
    const double d = pair_distance_m(net, e);
    seen[a] += point_view_factor(net.radius_m[b], d);
    seen[b] += point_view_factor(net.radius_m[a], d);
  }
  if (walls)
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w)
      if (radiating_wall(net, w, reach)) ++wall_count[net.wall_node[w]];
  for (std::size_t i = 0; i < n; ++i) {
    const double open = std::max(1.0 - seen[i], 0.0);
    if (wall_count[i] > 0) s.wall_share[i] = open / std::max(2, wall_count[i]);
    const double to_walls = wall_count[i] * s.wall_share[i];
    if (!enclosed) {
      s.open_share[i] = open - to_walls;
      continue;
    }
    s.open_share[i] = 0.0;
    const double total = seen[i] + to_walls;
    s.pair_scale[i] = total > 0.0 ? 1.0 / total : 0.0;
    s.wall_share[i] *= s.pair_scale[i];
  }
  return s;
}

inline ModeParameter between_particles_parameter() {
  return {.key = "between_particles",
          .default_value = 0.0,
          .range = ParameterRange::any(),
          .description = "also exchange radiation between neighbouring particles (view factor of "
                         "a sphere seen from its neighbour's centre) and with the isothermal walls "
                         "near them (see walls); what meets them no longer reaches the surroundings",
          .boolean = true};
}

inline ModeParameter pair_cutoff_parameter() {
  return {.key = "pair_cutoff",
          .unit = "",
          .default_value = 0.5,
          .range = ParameterRange::open_closed(0.0, 6.0),
          .description = "largest gap of a radiating pair or particle-wall pair, as a fraction of "
                         "the smaller radius; a pair whose centre line a third particle crosses "
                         "does not exchange (4 for an enclosed bed: docs/validation.md)"};
}

inline ModeParameter walls_parameter() {
  return {.key = "walls",
          .default_value = 1.0,
          .range = ParameterRange::any(),
          .description = "with between_particles: isothermal walls within pair_cutoff exchange "
                         "radiation with the particle (view factor half the share its radiating "
                         "neighbours leave open; emissivity of the wall's material)",
          .boolean = true};
}

inline ModeParameter surroundings_parameter() {
  return {.key = "surroundings",
          .default_value = 1.0,
          .range = ParameterRange::any(),
          .description = "particles radiate what their neighbours and walls leave open to the "
                         "surroundings at ambient_temperature; false for an enclosed bed (between "
                         "walls, periodic): nothing leaves, and with between_particles each "
                         "particle's view factors are scaled to sum to 1",
          .boolean = true};
}

}  // namespace tmdem::thermal
