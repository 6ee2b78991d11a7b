// Conduction through the stagnant gas between particles, and between a particle and an
// isothermal wall, across touching and near pairs: q_a += H_g (T_b - T_a). H_g depends only on
// the geometry of the frozen packing, so it is computed once per edge set (update_geometry) and
// enters the Laplacian like contact conduction, with the same exact (constant) Jacobian.
// Models: thermal/modes/GasGapConductance.h; docs/heat-modes.md "Gas in the gaps".
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

enum class GasModel { VargasMcCarthy, SurroundingLayer, Bahrami };

GasModel model_of(std::string_view name) {
  if (name == "surrounding_layer") return GasModel::SurroundingLayer;
  if (name == "bahrami") return GasModel::Bahrami;
  return GasModel::VargasMcCarthy;
}

class GasConductionMode final : public HeatTransferMode {
 public:
  explicit GasConductionMode(const ModeParameters& p)
      : k_f_W_per_mK_(p["conductivity"]),
        model_(model_of(p.choice("model"))),
        share_(p.choice("layer_share") == "equal_solid_angle"),
        reach_(p["cutoff"]),
        min_gap_m_(p["min_gap"]),
        jump_m_(gas_jump_length_m(p["pressure"], p["mean_free_path"], p["accommodation"])),
        gas_parameter_m_(gas_parameter_m(p["pressure"], p["mean_free_path"], p["accommodation"],
                                         p["accommodation"], p["heat_capacity_ratio"],
                                         p["prandtl"])) {}

  std::string_view name() const override { return "gas_conduction"; }

  void update_geometry(const ThermalNetwork& net) override {
    count_neighbours(net);
    compute_conductances(net);
  }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    // A network other than the system's (the conductivity study's wall-filtered copies): its
    // conductances from its own geometry, computed here, not the cached ones.
    if (!is_cached(net)) return GasConductionMode(*this, net).add_heat_flow(net, T, q, boundary_W);
    const auto* held = net.held.data();
    for (std::size_t e = 0; e < H_edge_.size(); ++e) {
      const auto a = net.edge_a[e], b = net.edge_b[e];
      const double flow_into_a = H_edge_[e] * edge_factor(net, e) * (T[b] - T[a]);
      q[a] += flow_into_a;
      q[b] -= flow_into_a;
      if (held[a] != held[b]) boundary_W += held[a] ? -flow_into_a : flow_into_a;
    }
    for (std::size_t w = 0; w < H_wall_.size(); ++w) {
      const auto i = net.wall_node[w];
      const double flow = H_wall_[w] * wall_factor(net, w) * (net.wall_temperature_K[w] - T[i]);
      q[i] += flow;
      if (!held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    if (!is_cached(net)) return GasConductionMode(*this, net).add_jacobian(net, T, J);
    for (std::size_t e = 0; e < H_edge_.size(); ++e) {
      const double h = H_edge_[e] * edge_factor(net, e);
      J.edge_W_per_K[e] += h;
      J.diagonal_W_per_K[net.edge_a[e]] -= h;
      J.diagonal_W_per_K[net.edge_b[e]] -= h;
    }
    for (std::size_t w = 0; w < H_wall_.size(); ++w)
      J.diagonal_W_per_K[net.wall_node[w]] -= H_wall_[w] * wall_factor(net, w);
  }

  // The gas shares the solid near the contact with contact conduction: its H_g joins the pair's
  // sum before the particle's own resistance is put in series (ParticleResistance.h). With the
  // shells per ray the gas holds its own shells and stays out of that sum.
  bool add_pair_conductance(const ThermalNetwork& net, std::span<double> edge_W_per_K,
                            std::span<double> wall_W_per_K) const override {
    if (rays(net)) return true;
    if (!is_cached(net)) return GasConductionMode(*this, net).add_pair_conductance(net, edge_W_per_K, wall_W_per_K);
    for (std::size_t e = 0; e < H_edge_.size(); ++e) edge_W_per_K[e] += H_edge_[e];
    for (std::size_t w = 0; w < H_wall_.size(); ++w) wall_W_per_K[w] += H_wall_[w];
    return true;
  }

 private:
  // The shells per ray are the surrounding layer's; the Vargas-McCarthy closed form has no rays
  // and keeps the lumped shells (the scene refuses that pairing; a network built by hand gets it).
  bool rays(const ThermalNetwork& net) const {
    return net.gas_shells_per_ray && model_ == GasModel::SurroundingLayer;
  }
  // The lumped shells' factor (ParticleResistance.h), or 1 where the gas holds its shells per ray.
  double edge_factor(const ThermalNetwork& net, std::size_t e) const {
    return rays(net) ? 1.0 : net.edge_factor(e);
  }
  double wall_factor(const ThermalNetwork& net, std::size_t w) const {
    return rays(net) ? 1.0 : net.wall_factor(w);
  }

  // A view of the system's network with some wall edges left out (the conductivity study's
  // per-wall flows) keeps the system's shares, so its flows add up to the system's; any other
  // network is counted afresh.
  GasConductionMode(const GasConductionMode& settings, const ThermalNetwork& net)
      : k_f_W_per_mK_(settings.k_f_W_per_mK_), model_(settings.model_), share_(settings.share_),
        reach_(settings.reach_),
        min_gap_m_(settings.min_gap_m_), jump_m_(settings.jump_m_),
        gas_parameter_m_(settings.gas_parameter_m_) {
    if (net.edge_a == settings.cached_edge_a_ && net.edge_b == settings.cached_edge_b_ &&
        net.node_count() == settings.neighbours_.size())
      neighbours_ = settings.neighbours_;
    else
      count_neighbours(net);
    compute_conductances(net);
  }

  void compute_conductances(const ThermalNetwork& net) {
    H_edge_.assign(net.edge_count(), 0.0);
    for (std::size_t e = 0; e < net.edge_count(); ++e) H_edge_[e] = edge_conductance(net, e);
    H_wall_.assign(net.wall_edge_count(), 0.0);
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) H_wall_[w] = wall_conductance(net, w);
    cached_edge_a_ = net.edge_a;
    cached_edge_b_ = net.edge_b;
    cached_wall_node_ = net.wall_node;
  }

  bool is_cached(const ThermalNetwork& net) const {
    return net.edge_a == cached_edge_a_ && net.edge_b == cached_edge_b_ &&
           net.wall_node == cached_wall_node_;
  }

  GasGap edge_gap(const ThermalNetwork& net, std::size_t e) const {
    GasGap g{net.radius_m[net.edge_a[e]], net.radius_m[net.edge_b[e]], net.edge_gap_m[e],
             net.edge_contact_radius_m[e]};
    if (rays(net)) {
      g.shell_gap_a_m = shell_gap_m(net, net.edge_a[e]);
      g.shell_gap_b_m = shell_gap_m(net, net.edge_b[e]);
    }
    return g;
  }

  GasGap wall_gap(const ThermalNetwork& net, std::size_t w) const {
    GasGap g;
    g.radius_a_m = net.radius_m[net.wall_node[w]];
    g.gap_m = net.wall_gap_m[w];
    g.contact_radius_m = net.wall_contact_radius_m[w];
    if (rays(net)) g.shell_gap_a_m = shell_gap_m(net, net.wall_node[w]);
    return g;
  }

  // Node i's shell as a gas thickness on its axial ray, k_f S r^2 (GasGap::shell_gap_a_m), m.
  double shell_gap_m(const ThermalNetwork& net, std::int32_t i) const {
    const double r = net.radius_m[std::size_t(i)];
    return k_f_W_per_mK_ * net.shell_resistance_K_sr_per_W[std::size_t(i)] * r * r;
  }

  // layer_share = "equal_solid_angle": per particle the number z of its pairs (particles and
  // isothermal walls) inside the layer, whose gas it shares equally (equal_share_disk_radius_m).
  void count_neighbours(const ThermalNetwork& net) {
    neighbours_.clear();
    if (!share_ || model_ != GasModel::SurroundingLayer) return;
    neighbours_.assign(net.node_count(), 0);
    for (std::size_t e = 0; e < net.edge_count(); ++e)
      if (surrounding_layer_reaches(edge_gap(net, e), reach_)) {
        ++neighbours_[net.edge_a[e]];
        ++neighbours_[net.edge_b[e]];
      }
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w)
      if (surrounding_layer_reaches(wall_gap(net, w), reach_)) ++neighbours_[net.wall_node[w]];
  }

  // The pair's disk: the smaller of its particles' equal shares (infinity without sharing).
  double share_radius_m(const ThermalNetwork& net, std::int32_t node) const {
    if (neighbours_.empty()) return std::numeric_limits<double>::infinity();
    return equal_share_disk_radius_m(net.radius_m[node], neighbours_[node]);
  }

  double edge_conductance(const ThermalNetwork& net, std::size_t e) const {
    const double disk =
        std::min(share_radius_m(net, net.edge_a[e]), share_radius_m(net, net.edge_b[e]));
    return conductance(edge_gap(net, e), net.edge_in_contact[e] != 0, disk);
  }

  double wall_conductance(const ThermalNetwork& net, std::size_t w) const {
    return conductance(wall_gap(net, w), net.wall_in_contact[w] != 0,
                       share_radius_m(net, net.wall_node[w]));
  }

  double conductance(const GasGap& g, bool in_contact, double disk_radius_m) const {
    const bool touching = in_contact || g.gap_m <= 0.0;
    if (model_ == GasModel::VargasMcCarthy)
      return touching ? vargas_mccarthy_conductance_W_per_K(g, k_f_W_per_mK_) : 0.0;
    if (model_ == GasModel::Bahrami)
      return touching ? bahrami_macrogap_conductance_W_per_K(g, k_f_W_per_mK_, gas_parameter_m_) : 0.0;
    return surrounding_layer_conductance_W_per_K(g, k_f_W_per_mK_, reach_, min_gap_m_, jump_m_,
                                                 disk_radius_m);
  }

  double k_f_W_per_mK_;
  GasModel model_;
  bool share_;        // layer_share = "equal_solid_angle"
  double reach_;      // fraction of the smaller radius
  double min_gap_m_;  // L_min of the surrounding layer
  double jump_m_;     // Smoluchowski jump length of the gap's two surfaces, m (0: continuum)
  double gas_parameter_m_;  // Bahrami's gas parameter M of the gap's two surfaces, m (0: continuum)
  std::vector<std::size_t> neighbours_;  // per node, when sharing: pairs inside the layer
  std::vector<double> H_edge_, H_wall_;  // W/K, per edge of the current geometry
  std::vector<std::int32_t> cached_edge_a_, cached_edge_b_, cached_wall_node_;  // that geometry
};

}  // namespace

const ModeDescription& gas_conduction_mode() {
  static const ModeDescription mode{
      .name = "gas_conduction",
      .summary = "conduction through the stagnant gas between particles and to isothermal walls, "
                 "H_g (T_b - T_a) over touching and near pairs",
      .effect = "gas_conduction",
      .effect_description = "conduction through the interstitial gas, see [fluid]",
      .section = "fluid",
      .section_description =
          "the stagnant interstitial fluid; used when effects.gas_conduction = true",
      .parameters = {{.key = "conductivity",
                      .unit = "W/(m K)",
                      .default_value = 0.0262,
                      .range = ParameterRange::greater(0.0),
                      .description = "fluid thermal conductivity k_f (air at 300 K: 0.0262)"},
                     {.key = "model",
                      .range = ParameterRange::any(),
                      .description = "gas-gap conductance model: \"vargas_mccarthy\" (touching "
                                     "pairs, Vargas & McCarthy 2002), \"surrounding_layer\" "
                                     "(touching and near pairs, Rong & Horio 1999) or \"bahrami\" "
                                     "(touching pairs: the macro-gap of Bahrami, Yovanovich & "
                                     "Culham 2006 with the gas parameter M; needs pressure > 0)",
                      .choices = {"vargas_mccarthy", "surrounding_layer", "bahrami"}},
                     {.key = "layer_share",
                      .range = ParameterRange::any(),
                      .description = "how the surrounding layer's gas is shared between a "
                                     "particle's neighbours: \"none\" (every pair integrates over "
                                     "its whole layer, so overlapping layers count gas more than "
                                     "once) or \"equal_solid_angle\" (each pair's disk is clipped "
                                     "to the cone of solid angle 4 pi / z around its axis, z the "
                                     "particle's pairs inside the layer; needs model = "
                                     "\"surrounding_layer\")",
                      .choices = {"none", "equal_solid_angle"}},
                     {.key = "cutoff",
                      .unit = "",
                      .default_value = 0.4,
                      .range = ParameterRange::open_closed(0.0, 2.0),
                      .description = "largest gap that conducts, as a fraction of the smaller "
                                     "radius; the surrounding layer's thickness"},
                     {.key = "min_gap",
                      .unit = "m",
                      .default_value = 1.0e-7,
                      .range = ParameterRange::greater(0.0),
                      .description = "smallest gas thickness of the surrounding layer (surface "
                                     "roughness, gas mean free path: air 6.8e-8 m)"},
                     {.key = "pressure",
                      .unit = "Pa",
                      .default_value = 0.0,
                      .range = ParameterRange::at_least(0.0),
                      .description = "gas pressure for the rarefied-gas (Smoluchowski) reduction "
                                     "of the surrounding layer: each gap conducts as if wider by "
                                     "the jump length 2 (2 - accommodation) / accommodation x "
                                     "mean_free_path x 101325 Pa / pressure; 0: continuum gas, "
                                     "no reduction (needs model = \"surrounding_layer\" or "
                                     "\"bahrami\"; \"bahrami\" needs it > 0, and rough contacts, "
                                     "thermal.conductance = \"bahrami\", take their micro-gap's "
                                     "jump from it)"},
                     {.key = "mean_free_path",
                      .unit = "m",
                      .default_value = 6.8e-8,
                      .range = ParameterRange::greater(0.0),
                      .description = "mean free path of the gas molecules at 101325 Pa and the "
                                     "run's temperature (air at 300 K: 6.8e-8; helium: 1.9e-7)"},
                     {.key = "accommodation",
                      .unit = "",
                      .default_value = 0.9,
                      .range = ParameterRange::open_closed(0.0, 1.0),
                      .description = "thermal accommodation coefficient of the gas on the "
                                     "particle surfaces (air on glass near 300 K: 0.9, VDI Heat "
                                     "Atlas; helium much lower)"},
                     {.key = "heat_capacity_ratio",
                      .unit = "",
                      .default_value = 1.4,
                      .range = ParameterRange::closed(1.0, 2.0),
                      .description = "c_p / c_v of the gas, in Bahrami's gas parameter M (model = "
                                     "\"bahrami\" and rough contacts; air: 1.4, helium: 5/3)"},
                     {.key = "prandtl",
                      .unit = "",
                      .default_value = 0.71,
                      .range = ParameterRange::greater(0.0),
                      .description = "Prandtl number mu c_p / k_f of the gas, in Bahrami's gas "
                                     "parameter M (model = \"bahrami\" and rough contacts; air "
                                     "at 300 K: 0.71, helium: 0.67)"}},
      .near_pair_reach = "cutoff",
      .check = [](const ModeParameters& p) -> std::optional<ParameterProblem> {
        if (p["pressure"] > 0.0 && p.choice("model") == "vargas_mccarthy")
          return ParameterProblem{"pressure",
                                  "needs model = \"surrounding_layer\" or \"bahrami\" "
                                  "(\"vargas_mccarthy\" is a touching-pair closed form with no "
                                  "gas gap to rarefy)"};
        // The macro-gap's jump M closes its logarithm at the contact's rim: no continuum limit.
        if (!(p["pressure"] > 0.0) && p.choice("model") == "bahrami")
          return ParameterProblem{"pressure",
                                  "model = \"bahrami\" needs the gas pressure (> 0; 101325 for "
                                  "air at 1 atm): its gap conductance diverges at the contact's "
                                  "rim without the temperature jump M of a rarefied gas"};
        if (p.choice("layer_share") != "none" && p.choice("model") != "surrounding_layer")
          return ParameterProblem{"layer_share",
                                  "needs model = \"surrounding_layer\" (\"" +
                                      std::string(p.choice("model")) +
                                      "\" is a touching-pair closed form with no layer to share)"};
        return std::nullopt;
      },
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<GasConductionMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
