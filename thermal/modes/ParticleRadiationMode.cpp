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
// With the particle's own resistance (ThermalNetwork::shell_resistance_K_sr_per_W) the shells
// stand in series with the exchange: G (T_b^4 - T_a^4) = h (T_b - T_a) with the secant
// conductance h = G (T_a^2 + T_b^2) (T_a + T_b), and the flow becomes h (T_b - T_a) / (1 + h R),
// R = R_a + R_b the shells over the partner's cone (a wall: R_a over the mirror's), as for the
// contacts (ParticleResistance.h); its Jacobian is exact.
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "thermal/modes/ModeDescription.h"
#include "thermal/modes/PairRadiationGeometry.h"
#include "thermal/modes/ParticleResistance.h"

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
    // The shells in series depend on the geometry only: once per edge set, not per evaluation.
    R_.clear();
    if (!net.shell_resistance_K_sr_per_W.empty()) {
      R_.resize(net.edge_count());
      for (std::size_t e = 0; e < net.edge_count(); ++e)
        R_[e] = edge_shell_resistance_K_per_W(net, e, true) + edge_shell_resistance_K_per_W(net, e, false);
    }
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
      const double flow_into_a = exchange(G_[e], T[a], T[b], pair_shells(e)).W;
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
      const double flow = exchange(G, T[i], net.wall_temperature_K[w], wall_shells(net, w)).W;
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
      // q_a = W(T_a, T_b), q_b = -W.
      const Exchange x = exchange(G_[e], ta, tb, pair_shells(e));
      J.diagonal_W_per_K[a] += x.dW_dTa;
      J.diagonal_W_per_K[b] -= x.dW_dTb;
      J.edge_ab_W_per_K[e] += x.dW_dTb;
      J.edge_ba_W_per_K[e] -= x.dW_dTa;
    }
    if (!walls_) return;
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const auto i = net.wall_node[w];
      const double t = T[i] > 0.0 ? T[i] : 0.0;
      J.diagonal_W_per_K[i] += exchange(wall_G(net, w), t, net.wall_temperature_K[w], wall_shells(net, w)).dW_dTa;
    }
  }

 private:
  // G (T_b^4 - T_a^4) through shells of resistance R (K/W; 0: none) in series, into a, and its
  // derivatives by T_a and T_b. With R = 0 the flow is G (T_b^4 - T_a^4) itself.
  struct Exchange {
    double W, dW_dTa, dW_dTb;
  };
  static Exchange exchange(double G, double Ta, double Tb, double R) {
    const double ta2 = Ta * Ta, tb2 = Tb * Tb;
    if (R == 0.0) return {G * (tb2 * tb2 - ta2 * ta2), -(4.0 * G * Ta * Ta * Ta), 4.0 * G * Tb * Tb * Tb};
    const double s2 = ta2 + tb2, s1 = Ta + Tb, dT = Tb - Ta;
    const double h = G * s2 * s1;                  // secant conductance, W/K
    const double f = 1.0 / (1.0 + h * R);          // the shells' factor
    const double dg_dh = f * f;                    // d(h f)/dh
    const double dh_dTa = G * (2.0 * Ta * s1 + s2), dh_dTb = G * (2.0 * Tb * s1 + s2);
    return {h * f * dT, dg_dh * dh_dTa * dT - h * f, dg_dh * dh_dTb * dT + h * f};
  }
  // Shell resistances in series with pair e and wall edge w, K/W (0 without shells). The wall's
  // is evaluated per call, as wall_G, so that a study's copy with fewer wall edges gets its own.
  double pair_shells(std::size_t e) const { return R_.empty() ? 0.0 : R_[e]; }
  static double wall_shells(const ThermalNetwork& net, std::size_t w) {
    return net.shell_resistance_K_sr_per_W.empty() ? 0.0 : wall_shell_resistance_K_per_W(net, w);
  }

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
  std::vector<double> R_;  // K/W, the shells in series per edge (empty: no particle resistance)
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
