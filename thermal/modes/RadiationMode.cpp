// Radiation to the surroundings: q_i += eps_i sigma A_i f_i (T_amb^4 - T_i^4). Split
// OpenFOAM-style into the flow (constant part at the current T) and the exact linearisation
// d q_i / d T_i = -4 eps_i sigma A_i f_i T_i^3 for the Jacobian.
//
// f_i is the share of particle i's radiation that reaches the surroundings: 1, or with
// [radiation] between_particles = true what its radiating neighbours and walls leave open
// (RadiationShares, PairRadiationGeometry.h). What meets a neighbour or a wall is exchanged
// with it by the pair mode and must not also leave to the surroundings: for black spheres the
// two modes then account for each surface's emission exactly once. Built only while
// [radiation] surroundings = true.
#include <memory>
#include <optional>
#include <vector>

#include "thermal/modes/ModeDescription.h"
#include "thermal/modes/PairRadiationGeometry.h"

namespace tmdem::thermal {
namespace {

class RadiationMode final : public HeatTransferMode {
 public:
  explicit RadiationMode(const ModeParameters& p)
      : ambient_K_(p["ambient_temperature"]),
        pairs_(p["between_particles"] != 0.0),
        walls_(p["walls"] != 0.0),
        reach_(p["pair_cutoff"]) {}

  std::string_view name() const override { return "radiation"; }

  void update_geometry(const ThermalNetwork& net) override {
    if (!pairs_) return;  // every share is 1
    open_share_ = radiation_shares(net, reach_, walls_, false).open_share;
    cached_edge_a_ = net.edge_a;
    cached_edge_b_ = net.edge_b;
  }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    // A network other than the system's (a study's filtered copy): its own shares.
    if (pairs_ && !is_cached(net)) return RadiationMode(*this, net).add_heat_flow(net, T, q, boundary_W);
    const double ambient4 = ambient_K_ * ambient_K_ * ambient_K_ * ambient_K_;
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      // A trial step may overshoot below 0 K; T^4 would then pump heat the wrong way. Refuse
      // so the integrator retries with a smaller step instead of producing nonsense or NaN.
      if (!(T[i] > 0.0)) return false;
      const double t2 = T[i] * T[i];
      const double flow = net.emissivity[i] * kStefanBoltzmann_W_per_m2K4 * net.surface_area_m2[i] *
                          open_share(i) * (ambient4 - t2 * t2);
      q[i] += flow;
      if (!net.held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    if (pairs_ && !is_cached(net)) return RadiationMode(*this, net).add_jacobian(net, T, J);
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      const double t = T[i] > 0.0 ? T[i] : 0.0;
      J.diagonal_W_per_K[i] -= 4.0 * net.emissivity[i] * kStefanBoltzmann_W_per_m2K4 *
                               net.surface_area_m2[i] * open_share(i) * t * t * t;
    }
  }

 private:
  RadiationMode(const RadiationMode& settings, const ThermalNetwork& net)
      : ambient_K_(settings.ambient_K_), pairs_(settings.pairs_), walls_(settings.walls_),
        reach_(settings.reach_) {
    update_geometry(net);
  }
  double open_share(std::size_t i) const { return pairs_ ? open_share_[i] : 1.0; }
  bool is_cached(const ThermalNetwork& net) const {
    return open_share_.size() == net.node_count() && net.edge_a == cached_edge_a_ &&
           net.edge_b == cached_edge_b_;
  }

  double ambient_K_;
  bool pairs_;    // [radiation] between_particles: neighbours shade the surroundings
  bool walls_;    // [radiation] walls: so do the isothermal walls within reach
  double reach_;  // [radiation] pair_cutoff, fraction of the smaller radius
  std::vector<double> open_share_;  // f_i, per node of the current geometry
  std::vector<std::int32_t> cached_edge_a_, cached_edge_b_;  // that geometry
};

}  // namespace

const ModeDescription& radiation_mode() {
  static const ModeDescription mode{
      .name = "radiation",
      .summary = "radiation to the surroundings, eps_i sigma 4 pi r^2 f_i (T_amb^4 - T_i^4), f_i "
                 "the share not seen by radiating neighbours and walls",
      .effect = "radiation",
      .effect_description = "particle-ambient radiation, see [radiation]",
      .section = "radiation",
      .section_description = "particle-ambient radiation; used when effects.radiation = true",
      .parameters = {{.key = "ambient_temperature",
                      .unit = "K",
                      .default_value = 293.15,
                      .range = ParameterRange::at_least(0.0),
                      .description = "temperature of the surroundings; emissivity comes from each "
                                     "particle's material",
                      .bounds_temperature = true},
                     between_particles_parameter(),
                     pair_cutoff_parameter(),
                     walls_parameter(),
                     surroundings_parameter()},
      .enabled_by = "surroundings",
      .check = [](const ModeParameters& p) -> std::optional<ParameterProblem> {
        if (p["surroundings"] == 0.0 && p["between_particles"] == 0.0)
          return ParameterProblem{"surroundings",
                                  "false with between_particles = false leaves radiation nothing "
                                  "to exchange: set between_particles = true (an enclosed bed), "
                                  "or effects.radiation = false"};
        return std::nullopt;
      },
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<RadiationMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
