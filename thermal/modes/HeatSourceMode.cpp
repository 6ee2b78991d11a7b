// Imposed heat sources: q_i += P_i (W). Constant in T, so nothing enters the Jacobian.
#include <memory>

#include <algorithm>

#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class HeatSourceMode final : public HeatTransferMode {
 public:
  std::string_view name() const override { return "heat_source"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double>,
                     std::span<double> q, double& boundary_W) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      q[i] += net.heat_source_W[i];
      if (!net.held[i]) boundary_W += net.heat_source_W[i];
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork&, std::span<const double>, JacobianView) const override {}

  // f_i = P_i, nothing in K.
  bool add_affine_heat_flow(const ThermalNetwork& net, AffineHeatFlow& out) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) out.constant_W[i] += net.heat_source_W[i];
    return true;
  }
};

}  // namespace

const ModeDescription& heat_source_mode() {
  static const ModeDescription mode{
      .name = "heat_source",
      .summary = "imposed power P_i of the particles with a heat_source",
      .in_use =
          [](const ThermalNetwork& nodes) {
            return std::any_of(nodes.heat_source_W.begin(), nodes.heat_source_W.end(),
                               [](double P_W) { return P_W != 0.0; });
          },
      .make = [](const ModeParameters&) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<HeatSourceMode>();
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
