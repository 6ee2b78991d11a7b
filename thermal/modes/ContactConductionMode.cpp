// Particle-particle contact conduction: q_a += H (T_b - T_a), q_b -= the same value, so every
// edge is exactly conservative (the flow one node gains is the flow the other loses, bit for bit).
#include <memory>

#include "thermal/modes/KirchhoffContactFlow.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::thermal {
namespace {

class ContactConductionMode final : public HeatTransferMode {
 public:
  // With k(T) (ThermalNetwork::conductance_follows_conductivity): the flow from b into a, with
  // 2 a recovered from H at the reference conductivities.
  static ContactFlow flow(const ThermalNetwork& net, std::size_t e, std::span<const double> T) {
    const auto a = std::size_t(net.edge_a[e]), b = std::size_t(net.edge_b[e]);
    const auto& ka = net.material_conductivity[std::size_t(net.node_material[a])];
    const auto& kb = net.material_conductivity[std::size_t(net.node_material[b])];
    const double two_a =
        net.edge_conductance_W_per_K[e] / harmonic_mean_conductivity(ka.y.front(), kb.y.front());
    return kirchhoff_contact_flow(two_a, kb, T[b], ka, T[a]);
  }

  std::string_view name() const override { return "contact_conduction"; }

  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T,
                     std::span<double> q, double& boundary_W) const override {
    if (net.conductance_follows_conductivity) {
      for (std::size_t e = 0; e < net.edge_count(); ++e) {
        const auto a = std::size_t(net.edge_a[e]), b = std::size_t(net.edge_b[e]);
        const double flow_into_a = flow(net, e, T).W;
        q[a] += flow_into_a;
        q[b] -= flow_into_a;
        if (net.held[a] != net.held[b]) boundary_W += net.held[a] ? -flow_into_a : flow_into_a;
      }
      return true;
    }
    const std::size_t m = net.edge_count();
    const auto* a = net.edge_a.data();
    const auto* b = net.edge_b.data();
    const auto* H = net.edge_conductance_W_per_K.data();
    const auto* held = net.held.data();
    // The particle's own resistance (ThermalNetwork::edge_series_factor): H' = f H. Without it
    // the loop is today's, bit for bit.
    const auto* f = net.edge_series_factor.empty() ? nullptr : net.edge_series_factor.data();
    for (std::size_t e = 0; e < m; ++e) {
      const double h = f ? H[e] * f[e] : H[e];
      const double flow_into_a = h * (T[b[e]] - T[a[e]]);
      q[a[e]] += flow_into_a;
      q[b[e]] -= flow_into_a;
      // A held particle is a reservoir: what it gives a free neighbour enters the free system.
      if (held[a[e]] != held[b[e]]) boundary_W += held[a[e]] ? -flow_into_a : flow_into_a;
    }
    return true;
  }

  bool add_pair_conductance(const ThermalNetwork& net, std::span<double> edge_W_per_K,
                            std::span<double> /*wall_W_per_K*/) const override {
    for (std::size_t e = 0; e < net.edge_count(); ++e) edge_W_per_K[e] += net.edge_conductance_W_per_K[e];
    return true;
  }

  void add_jacobian(const ThermalNetwork& net, std::span<const double> T,
                    JacobianView J) const override {
    if (net.conductance_follows_conductivity) {
      // flow into a = Q(b -> a): d q_a / d T_b = dQ/dT1, d q_a / d T_a = dQ/dT2, q_b = -q_a.
      for (std::size_t e = 0; e < net.edge_count(); ++e) {
        const ContactFlow f = flow(net, e, T);
        J.diagonal_W_per_K[std::size_t(net.edge_a[e])] += f.dW_dT2;
        J.diagonal_W_per_K[std::size_t(net.edge_b[e])] -= f.dW_dT1;
        J.edge_ab_W_per_K[e] += f.dW_dT1;
        J.edge_ba_W_per_K[e] -= f.dW_dT2;
      }
      return;
    }
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      const double h = net.edge_conductance_W_per_K[e] * net.edge_factor(e);
      J.edge_W_per_K[e] += h;
      J.diagonal_W_per_K[net.edge_a[e]] -= h;
      J.diagonal_W_per_K[net.edge_b[e]] -= h;
    }
  }

  // H (T_b - T_a) into a and its opposite into b: K_ab = K_ba = H, K_aa = K_bb = -H (H' = f H
  // with the particle's own resistance). With k(T) the flow is not affine.
  bool add_affine_heat_flow(const ThermalNetwork& net, AffineHeatFlow& out) const override {
    if (net.conductance_follows_conductivity) return false;
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      const std::int64_t a = net.edge_a[e], b = net.edge_b[e];
      const double h = net.edge_conductance_W_per_K[e] * net.edge_factor(e);
      out.add(a, b, h);
      out.add(b, a, h);
      out.add(a, a, -h);
      out.add(b, b, -h);
    }
    return true;
  }
};

}  // namespace

const ModeDescription& contact_conduction_mode() {
  static const ModeDescription mode{
      .name = "contact_conduction",
      .summary = "particle-particle contact conduction, H (T_b - T_a) per contact",
      .effect = "conduction",
      .effect_default = true,
      .effect_description = "particle-particle and particle-wall contact conduction",
      .uses_contact_conductance = true,
      .make = [](const ModeParameters&) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<ContactConductionMode>();
      },
  };
  return mode;
}

}  // namespace tmdem::thermal
