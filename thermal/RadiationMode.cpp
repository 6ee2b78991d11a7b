// Radiation to the surroundings: q_i += eps_i sigma A_i (T_amb^4 - T_i^4). Split OpenFOAM-style
// into the flow (constant part at the current T) and the exact linearisation
// d q_i / d T_i = -4 eps_i sigma A_i T_i^3 for the Jacobian.
#include <memory>

#include "thermal/ModeDescription.h"

namespace tmdem::thermal {
namespace {

constexpr double kStefanBoltzmann_W_per_m2K4 = 5.670374419e-8;

class RadiationMode final : public HeatTransferMode {
 public:
  explicit RadiationMode(const ModeParameters& p) : ambient_K_(p["ambient_temperature"]) {}

  std::string_view name() const override { return "radiation"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    const double ambient4 = ambient_K_ * ambient_K_ * ambient_K_ * ambient_K_;
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      // A trial step may overshoot below 0 K; T^4 would then pump heat the wrong way. Refuse
      // so the integrator retries with a smaller step instead of producing nonsense or NaN.
      if (!(T[i] > 0.0)) return false;
      const double t2 = T[i] * T[i];
      const double flow =
          net.emissivity[i] * kStefanBoltzmann_W_per_m2K4 * net.surface_area_m2[i] * (ambient4 - t2 * t2);
      q[i] += flow;
      if (!net.held[i]) boundary_W += flow;
    }
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      const double t = T[i] > 0.0 ? T[i] : 0.0;
      J.diagonal_W_per_K[i] -=
          4.0 * net.emissivity[i] * kStefanBoltzmann_W_per_m2K4 * net.surface_area_m2[i] * t * t * t;
    }
  }

 private:
  double ambient_K_;
};

}  // namespace

const ModeDescription& radiation_mode() {
  static const ModeDescription mode{
      .name = "radiation",
      .summary = "radiation to the surroundings, eps_i sigma 4 pi r^2 (T_amb^4 - T_i^4)",
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
                      .bounds_temperature = true}},
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<RadiationMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
