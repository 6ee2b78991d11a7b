// Radiation between neighbouring particles, and between particles and the isothermal walls
// near them: q_a += G_ab (T_b^4 - T_a^4), q_b -= the same, with
//   G_ab = sigma eps_eff (A_a F_ab s_a + A_b F_ba s_b) / 2,   eps_eff = 1 / (1/eps_a + 1/eps_b - 1),
//   F_ab = (1 - sqrt(1 - (r_b / d)^2)) / 2
// F_ab is the share of the radiation leaving the centre of a that meets sphere b (exact for a
// small emitter, the far-field limit r_b^2 / (4 d^2) of the sphere-to-sphere view factor); the
// average makes G symmetric, so every pair conserves energy exactly. s_a is 1, or in an
// enclosed bed ([radiation] surroundings = false) the scale that makes a's view factors sum to
// 1 (PairRadiationGeometry.h). A wall within reach takes q_a += sigma eps_eff A_a F_aw
// (T_w^4 - T_a^4), F_aw the wall share of PairRadiationGeometry.h. Pairs beyond [radiation]
// pair_cutoff, and pairs whose centre line a third particle crosses (ThermalNetwork::
// edge_shadowed, coupling/bridge/LineOfSight.h), are left out. What meets a neighbour or a wall
// does not also reach the surroundings (RadiationMode.cpp). Exact Jacobian, one-sided:
// d q_a / d T_b = 4 G T_b^3, d q_b / d T_a = 4 G T_a^3. docs/heat-modes.md "Radiation to the
// surroundings and between particles".
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "thermal/modes/ModeDescription.h"
#include "thermal/modes/PairRadiationGeometry.h"

namespace tmdem::thermal {
namespace {

class ParticleRadiationMode final : public HeatTransferMode {
 public:
  explicit ParticleRadiationMode(const ModeParameters& p)
      : reach_(p["pair_cutoff"]), walls_(p["walls"] != 0.0), enclosed_(p["surroundings"] == 0.0) {}

  std::string_view name() const override { return "particle_radiation"; }
  bool symmetric_jacobian() const override { return false; }

  void update_geometry(const ThermalNetwork& net) override {
    shares_ = radiation_shares(net, reach_, walls_, enclosed_);
    G_.assign(net.edge_count(), 0.0);
    const double pi = std::numbers::pi;
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      if (!radiating_pair(net, e, reach_)) continue;
      const auto a = net.edge_a[e], b = net.edge_b[e];
      const double ra = net.radius_m[a], rb = net.radius_m[b];
      const double d = pair_distance_m(net, e);
      const double AF = 0.5 * (4.0 * pi * ra * ra * point_view_factor(rb, d) * shares_.pair_scale[a] +
                               4.0 * pi * rb * rb * point_view_factor(ra, d) * shares_.pair_scale[b]);
      G_[e] = kStefanBoltzmann_W_per_m2K4 * exchange_emissivity(net.emissivity[a], net.emissivity[b]) * AF;
    }
    cached_edge_a_ = net.edge_a;
    cached_edge_b_ = net.edge_b;
  }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    // A network other than the system's (a study's filtered copy): its own view factors.
    if (!is_cached(net)) return ParticleRadiationMode(*this, net).add_heat_flow(net, T, q, boundary_W);
    const auto* held = net.held.data();
    for (std::size_t e = 0; e < G_.size(); ++e) {
      if (G_[e] == 0.0) continue;
      const auto a = net.edge_a[e], b = net.edge_b[e];
      // Below 0 K T^4 would pump heat the wrong way: a recoverable failure (smaller step).
      if (!(T[a] > 0.0) || !(T[b] > 0.0)) return false;
      const double ta2 = T[a] * T[a], tb2 = T[b] * T[b];
      const double flow_into_a = G_[e] * (tb2 * tb2 - ta2 * ta2);
      q[a] += flow_into_a;
      q[b] -= flow_into_a;
      if (held[a] != held[b]) boundary_W += held[a] ? -flow_into_a : flow_into_a;
    }
    if (!walls_) return true;
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const double G = wall_G(net, w);
      if (G == 0.0) continue;
      const auto i = net.wall_node[w];
      if (!(T[i] > 0.0)) return false;
      const double ti2 = T[i] * T[i], tw2 = net.wall_temperature_K[w] * net.wall_temperature_K[w];
      const double flow = G * (tw2 * tw2 - ti2 * ti2);
      q[i] += flow;
      if (!held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    if (!is_cached(net)) return ParticleRadiationMode(*this, net).add_jacobian(net, T, J);
    for (std::size_t e = 0; e < G_.size(); ++e) {
      if (G_[e] == 0.0) continue;
      const auto a = net.edge_a[e], b = net.edge_b[e];
      const double ta = T[a] > 0.0 ? T[a] : 0.0, tb = T[b] > 0.0 ? T[b] : 0.0;
      const double da = 4.0 * G_[e] * ta * ta * ta, db = 4.0 * G_[e] * tb * tb * tb;
      J.diagonal_W_per_K[a] -= da;
      J.diagonal_W_per_K[b] -= db;
      J.edge_ab_W_per_K[e] += db;
      J.edge_ba_W_per_K[e] += da;
    }
    if (!walls_) return;
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const auto i = net.wall_node[w];
      const double t = T[i] > 0.0 ? T[i] : 0.0;
      J.diagonal_W_per_K[i] -= 4.0 * wall_G(net, w) * t * t * t;
    }
  }

 private:
  ParticleRadiationMode(const ParticleRadiationMode& settings, const ThermalNetwork& net)
      : reach_(settings.reach_), walls_(settings.walls_), enclosed_(settings.enclosed_) {
    update_geometry(net);
  }
  // W/K^4 of wall edge w (0 when it does not radiate). From the edge and the node's wall
  // share, so that a study's copy with fewer wall edges gets the same value per edge.
  double wall_G(const ThermalNetwork& net, std::size_t w) const {
    if (!radiating_wall(net, w, reach_)) return 0.0;
    const auto i = net.wall_node[w];
    return kStefanBoltzmann_W_per_m2K4 * exchange_emissivity(net.emissivity[i], net.wall_emissivity[w]) *
           net.surface_area_m2[i] * shares_.wall_share[i];
  }
  bool is_cached(const ThermalNetwork& net) const {
    return net.edge_a == cached_edge_a_ && net.edge_b == cached_edge_b_;
  }

  double reach_;           // fraction of the smaller radius
  bool walls_;             // [radiation] walls
  bool enclosed_;          // [radiation] surroundings = false
  RadiationShares shares_;  // per node, of the current geometry
  std::vector<double> G_;  // W/K^4, per edge of the current geometry
  std::vector<std::int32_t> cached_edge_a_, cached_edge_b_;  // that geometry
};

}  // namespace

const ModeDescription& particle_radiation_mode() {
  static const ModeDescription mode{
      .name = "particle_radiation",
      .summary = "radiation between neighbouring particles and with the isothermal walls near "
                 "them, sigma eps_eff F A (T_b^4 - T_a^4)",
      .effect = "radiation",
      .effect_description = "particle-ambient radiation, see [radiation]",
      .section = "radiation",
      .section_description = "particle-ambient radiation; used when effects.radiation = true",
      .parameters = {between_particles_parameter(), pair_cutoff_parameter(), walls_parameter(),
                     surroundings_parameter()},
      .near_pair_reach = "pair_cutoff",
      .needs_line_of_sight = true,
      .enabled_by = "between_particles",
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<ParticleRadiationMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
