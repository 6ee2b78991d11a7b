// Particle-fluid convection on the sphere surface: q_i += h A_i (T_f - T_i), A_i = 4 pi r_i^2.
#include <memory>

#include "thermal/HeatTransferMode.h"

namespace tmdem::thermal {
namespace {

class ConvectionMode final : public HeatTransferMode {
 public:
  explicit ConvectionMode(const ModeSettings& s)
      : h_W_per_m2K_(s.convection_coefficient_W_per_m2K), fluid_K_(s.fluid_temperature_K) {}

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

 private:
  double h_W_per_m2K_;
  double fluid_K_;
};

}  // namespace

std::unique_ptr<HeatTransferMode> make_convection_mode(const ModeSettings& s) {
  return std::make_unique<ConvectionMode>(s);
}

}  // namespace tmdem::thermal
