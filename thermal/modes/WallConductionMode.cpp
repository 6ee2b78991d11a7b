// Particle-wall contact conduction with isothermal walls: q_i += H_iw (T_w - T_i).
// Adiabatic walls have no edge in the network, so they exchange nothing.
#include <memory>

#include "thermal/modes/KirchhoffContactFlow.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class WallConductionMode final : public HeatTransferMode {
 public:
  std::string_view name() const override { return "wall_conduction"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const auto i = net.wall_node[w];
      const double flow = net.conductance_follows_conductivity
                              ? wall_flow(net, w, T).W
                              : net.wall_conductance_W_per_K[w] * net.wall_factor(w) *
                                    (net.wall_temperature_K[w] - T[i]);
      q[i] += flow;
      if (!net.held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w)
      J.diagonal_W_per_K[net.wall_node[w]] += net.conductance_follows_conductivity
                                                  ? wall_flow(net, w, T).dW_dT2
                                                  : -net.wall_conductance_W_per_K[w] *
                                                        net.wall_factor(w);
  }

  bool add_pair_conductance(const ThermalNetwork& net, std::span<double> /*edge_W_per_K*/,
                            std::span<double> wall_W_per_K) const override {
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) wall_W_per_K[w] += net.wall_conductance_W_per_K[w];
    return true;
  }

  // H_iw (T_w - T_i): K_ii = -H_iw, f_i = H_iw T_w. With k(T) the flow is not affine.
  bool add_affine_heat_flow(const ThermalNetwork& net, AffineHeatFlow& out) const override {
    if (net.conductance_follows_conductivity) return false;
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const std::int64_t i = net.wall_node[w];
      const double h = net.wall_conductance_W_per_K[w] * net.wall_factor(w);
      out.add(i, i, -h);
      out.constant_W[std::size_t(i)] += h * net.wall_temperature_K[w];
    }
    return true;
  }

 private:
  // With k(T): the flow from the wall (its material at T_w) into the particle.
  static ContactFlow wall_flow(const ThermalNetwork& net, std::size_t w, std::span<const double> T) {
    const auto i = std::size_t(net.wall_node[w]);
    const auto& ki = net.material_conductivity[std::size_t(net.node_material[i])];
    const auto& kw = net.material_conductivity[std::size_t(net.wall_material[w])];
    const double two_a =
        net.wall_conductance_W_per_K[w] / harmonic_mean_conductivity(ki.y.front(), kw.y.front());
    return kirchhoff_contact_flow(two_a, kw, net.wall_temperature_K[w], ki, T[i]);
  }
};

}  // namespace

const ModeDescription& wall_conduction_mode() {
  static const ModeDescription mode{
      .name = "wall_conduction",
      .summary = "particle-wall contact conduction to isothermal walls, H (T_w - T_i)",
      .effect = "conduction",
      .effect_default = true,
      .effect_description = "particle-particle and particle-wall contact conduction",
      .uses_contact_conductance = true,
      .in_use = [](const ThermalNetwork& nodes) { return nodes.isothermal_walls > 0; },
      .make = [](const ModeParameters&) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<WallConductionMode>();
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
