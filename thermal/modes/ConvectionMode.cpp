// Particle-fluid convection on the sphere surface: q_i += h A_i (T_f - T_i), A_i = 4 pi r_i^2.
#include <memory>

#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class ConvectionMode final : public HeatTransferMode {
 public:
  explicit ConvectionMode(const ModeParameters& p)
      : h_W_per_m2K_(p["coefficient"]), fluid_K_(p["fluid_temperature"]) {}

  std::string_view name() const override { return "convection"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      const double flow = h_W_per_m2K_ * net.surface_area_m2[i] * (fluid_K_ - T[i]);
      q[i] += flow;
      if (!net.held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double>,
                    JacobianView J) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i)
      J.diagonal_W_per_K[i] -= h_W_per_m2K_ * net.surface_area_m2[i];
  }

  // h A_i (T_f - T_i): K_ii = -h A_i, f_i = h A_i T_f.
  bool add_affine_heat_flow(const ThermalNetwork& net, AffineHeatFlow& out) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      const double hA = h_W_per_m2K_ * net.surface_area_m2[i];
      out.add(std::int64_t(i), std::int64_t(i), -hA);
      out.constant_W[i] += hA * fluid_K_;
    }
    return true;
  }

 private:
  double h_W_per_m2K_;
  double fluid_K_;
};

}  // namespace

const ModeDescription& convection_mode() {
  static const ModeDescription mode{
      .name = "convection",
      .summary = "particle-fluid convection, h 4 pi r^2 (T_f - T_i)",
      .effect = "convection",
      .effect_description = "particle-fluid convection, see [convection]",
      .section = "convection",
      .section_description = "particle-fluid convection; used when effects.convection = true",
      .parameters = {{.key = "coefficient",
                      .unit = "W/(m^2 K)",
                      .default_value = 10.0,
                      .range = ParameterRange::at_least(0.0),
                      .description = "heat transfer coefficient h, on the sphere surface 4 pi r^2"},
                     {.key = "fluid_temperature",
                      .unit = "K",
                      .default_value = 293.15,
                      .range = ParameterRange::greater(0.0),
                      .description = "fluid temperature T_f",
                      .bounds_temperature = true}},
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<ConvectionMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
