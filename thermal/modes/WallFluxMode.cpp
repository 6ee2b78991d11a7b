// Walls with an imposed heat flux: wall w delivers the power P_w = flux x area (W), shared among
// the particles touching it in proportion to their contact conductance,
//   q_i += P_w H_iw / sum_k H_kw.
// The power does not depend on any temperature, so the Jacobian entry is exactly zero. A flux
// wall that touches nothing delivers nothing (the power has nowhere to go).
#include <memory>

#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class WallFluxMode final : public HeatTransferMode {
 public:
  std::string_view name() const override { return "wall_flux"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double>, std::span<double> q,
                     double& boundary_W) const override {
    // Flux walls are few (one or two): a pass per wall needs no scratch storage.
    for (std::size_t w = 0; w < net.flux_wall_power_W.size(); ++w) {
      double total_W_per_K = 0.0;
      for (std::size_t f = 0; f < net.flux_edge_count(); ++f)
        if (std::size_t(net.flux_wall[f]) == w) total_W_per_K += net.flux_conductance_W_per_K[f];
      if (!(total_W_per_K > 0.0)) continue;
      const double power_per_conductance = net.flux_wall_power_W[w] / total_W_per_K;  // K
      for (std::size_t f = 0; f < net.flux_edge_count(); ++f) {
        if (std::size_t(net.flux_wall[f]) != w) continue;
        const auto i = net.flux_node[f];
        const double flow = power_per_conductance * net.flux_conductance_W_per_K[f];
        q[i] += flow;
        if (!net.held[i]) boundary_W += flow;
      }
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork&, std::span<const double>, JacobianView) const override {}
};

}  // namespace

const ModeDescription& wall_flux_mode() {
  static const ModeDescription mode{
      .name = "wall_flux",
      .summary = "walls with an imposed heat flux: flux x area shared among their contacts by "
                 "conductance",
      .effect = "conduction",
      .effect_default = true,
      .effect_description = "particle-particle and particle-wall contact conduction",
      .uses_contact_conductance = true,
      .in_use = [](const ThermalNetwork& nodes) { return !nodes.flux_wall_power_W.empty(); },
      .make = [](const ModeParameters&) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<WallFluxMode>();
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
