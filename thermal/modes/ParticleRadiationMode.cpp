// Radiation between neighbouring particles: q_a += G_ab (T_b^4 - T_a^4), q_b -= the same, with
//   G_ab = sigma eps_eff (A_a F_ab + A_b F_ba) / 2,   eps_eff = 1 / (1/eps_a + 1/eps_b - 1),
//   F_ab = (1 - sqrt(1 - (r_b / d)^2)) / 2
// F_ab is the share of the radiation leaving the centre of a that meets sphere b (exact for a
// small emitter, the far-field limit r_b^2 / (4 d^2) of the sphere-to-sphere view factor); the
// average makes G symmetric, so every pair conserves energy exactly. No shadowing by third
// particles: pairs beyond [radiation] pair_cutoff are left out. The share F_ab of a's radiation
// that meets b does not also reach the surroundings (RadiationMode.cpp). Exact Jacobian, one-sided:
// d q_a / d T_b = 4 G T_b^3, d q_b / d T_a = 4 G T_a^3. docs/heat-modes.md "Radiation between particles".
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
  explicit ParticleRadiationMode(const ModeParameters& p) : reach_(p["pair_cutoff"]) {}

  std::string_view name() const override { return "particle_radiation"; }
  bool symmetric_jacobian() const override { return false; }

  void update_geometry(const ThermalNetwork& net) override {
    G_.assign(net.edge_count(), 0.0);
    const double pi = std::numbers::pi;
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      if (!radiating_pair(net, e, reach_)) continue;
      const auto a = net.edge_a[e], b = net.edge_b[e];
      const double ra = net.radius_m[a], rb = net.radius_m[b];
      const double ea = net.emissivity[a], eb = net.emissivity[b];
      const double eps = 1.0 / (1.0 / ea + 1.0 / eb - 1.0);
      const double d = pair_distance_m(net, e);
      const double AF = 0.5 * (4.0 * pi * ra * ra * point_view_factor(rb, d) +
                               4.0 * pi * rb * rb * point_view_factor(ra, d));
      G_[e] = kStefanBoltzmann_W_per_m2K4 * eps * AF;
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
  }

 private:
  ParticleRadiationMode(const ParticleRadiationMode& settings, const ThermalNetwork& net)
      : reach_(settings.reach_) {
    update_geometry(net);
  }
  bool is_cached(const ThermalNetwork& net) const {
    return net.edge_a == cached_edge_a_ && net.edge_b == cached_edge_b_;
  }

  double reach_;           // fraction of the smaller radius
  std::vector<double> G_;  // W/K^4, per edge of the current geometry
  std::vector<std::int32_t> cached_edge_a_, cached_edge_b_;  // that geometry
};

}  // namespace

const ModeDescription& particle_radiation_mode() {
  static const ModeDescription mode{
      .name = "particle_radiation",
      .summary = "radiation between neighbouring particles, sigma eps_eff F A (T_b^4 - T_a^4)",
      .effect = "radiation",
      .effect_description = "particle-ambient radiation, see [radiation]",
      .section = "radiation",
      .section_description = "particle-ambient radiation; used when effects.radiation = true",
      .parameters = {between_particles_parameter(), pair_cutoff_parameter()},
      .near_pair_reach = "pair_cutoff",
      .enabled_by = "between_particles",
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<ParticleRadiationMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
