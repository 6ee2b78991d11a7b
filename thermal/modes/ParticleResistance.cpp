#include "thermal/modes/ParticleResistance.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace tmdem::thermal {

double shell_resistance_K_sr_per_W(double radius_m, double conductivity_W_per_mK,
                                   double core_fraction) {
  return (1.0 / (core_fraction * radius_m) - 1.0 / radius_m) / conductivity_W_per_mK;
}

double partner_solid_angle_sr(double partner_radius_m, double centre_distance_m) {
  const double s = std::min(1.0, partner_radius_m / centre_distance_m);  // sin theta
  // 1 - cos theta = s^2 / (1 + cos theta): no cancellation for a small cone.
  return 2.0 * std::numbers::pi * s * s / (1.0 + std::sqrt(1.0 - s * s));
}

double edge_shell_resistance_K_per_W(const ThermalNetwork& net, std::size_t e, bool side_a) {
  const auto a = std::size_t(net.edge_a[e]), b = std::size_t(net.edge_b[e]);
  const auto self = side_a ? a : b, partner = side_a ? b : a;
  const double d = net.radius_m[a] + net.radius_m[b] + net.edge_gap_m[e];
  return net.shell_resistance_K_sr_per_W[self] / partner_solid_angle_sr(net.radius_m[partner], d);
}

double wall_shell_resistance_K_per_W(const ThermalNetwork& net, std::size_t w) {
  const auto i = std::size_t(net.wall_node[w]);
  const double r = net.radius_m[i];
  return net.shell_resistance_K_sr_per_W[i] /
         partner_solid_angle_sr(r, 2.0 * (r + net.wall_gap_m[w]));  // the mirror image
}

void update_series_factors(ThermalNetwork& net, std::span<const HeatTransferMode* const> modes) {
  net.edge_series_factor.clear();
  net.wall_series_factor.clear();
  if (net.shell_resistance_K_sr_per_W.empty()) return;
  std::vector<double> edge_H(net.edge_count(), 0.0), wall_H(net.wall_edge_count(), 0.0);
  for (const HeatTransferMode* mode : modes) mode->add_pair_conductance(net, edge_H, wall_H);
  std::vector<double> edge_f(net.edge_count(), 1.0), wall_f(net.wall_edge_count(), 1.0);
  for (std::size_t e = 0; e < edge_H.size(); ++e) {
    const double R = edge_shell_resistance_K_per_W(net, e, true) +
                     edge_shell_resistance_K_per_W(net, e, false);
    edge_f[e] = 1.0 / (1.0 + edge_H[e] * R);
  }
  for (std::size_t w = 0; w < wall_H.size(); ++w)
    wall_f[w] = 1.0 / (1.0 + wall_H[w] * wall_shell_resistance_K_per_W(net, w));
  net.edge_series_factor = std::move(edge_f);
  net.wall_series_factor = std::move(wall_f);
}

}  // namespace tmdem::thermal
