// Friction and impact heat: the mechanical energy each contact's impulse dissipates over a
// mechanical step (slip work plus impact loss, D_c = -r_c . u_theta,c; mechanics'
// NscdIntegrator.h) becomes heat in the two bodies, as a constant power D_c / h over that step.
// Partition: half to each body. A particle-particle contact heats both particles equally; at a
// particle-wall contact the particle gets half and the wall's half leaves the particles (walls
// have no heat capacity in the model: it is counted as lost to the wall). Half-half is the
// partition of two bodies of equal thermal effusivity; the heat does not depend on T, so
// nothing enters the Jacobian.
#include <memory>

#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class FrictionHeatMode final : public HeatTransferMode {
 public:
  std::string_view name() const override { return "friction_heat"; }
  bool heats_from_dissipation() const override { return true; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double>, std::span<double> q,
                     double& boundary_W) const override {
    for (std::size_t k = 0; k < net.dissipation_a.size(); ++k) {
      const double half_W = 0.5 * net.dissipation_W[k];
      for (const std::int32_t node : {net.dissipation_a[k], net.dissipation_b[k]}) {
        if (node < 0) continue;  // the wall's half
        q[std::size_t(node)] += half_W;
        // Mechanical energy entering the thermal side: boundary heat, as for a source.
        if (!net.held[std::size_t(node)]) boundary_W += half_W;
      }
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork&, std::span<const double>, JacobianView) const override {}
};

}  // namespace

const ModeDescription& friction_heat_mode() {
  static const ModeDescription mode{
      .name = "friction_heat",
      .summary = "mechanical energy dissipated at the contacts (slip, impact), half to each body",
      .effect = "friction_heat",
      .effect_description =
          "heat from friction and impacts: each contact's dissipated energy, half into each "
          "body (a wall's half is lost); needs mechanics = \"dynamic\"",
      .uses_contact_dissipation = true,
      .make = [](const ModeParameters&) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<FrictionHeatMode>();
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
