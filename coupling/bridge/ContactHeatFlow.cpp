#include "coupling/bridge/ContactHeatFlow.h"

#include "thermal/network/PiecewiseLinearTable.h"

namespace tmdem::coupling {
namespace {

double wall_temperature_K(const Wall& wall, double time_s) {
  if (wall.temperature_table.empty()) return *wall.temperature_K;
  thermal::PiecewiseLinearTable table;
  for (const auto& [t, T] : wall.temperature_table) {
    table.x.push_back(t);
    table.y.push_back(T);
  }
  return table(time_s);
}

}  // namespace

void contact_heat_flow_W(const ContactList& contacts, std::span<const double> conductance_W_per_K,
                         std::span<const double> temperature_K, double time_s, const Scene& scene,
                         std::vector<double>& out) {
  out.assign(contacts.size(), 0.0);
  std::vector<double> wall_T_K(scene.walls.size(), 0.0);
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].temperature_K) wall_T_K[w] = wall_temperature_K(scene.walls[w], time_s);
  std::vector<double> flux_conductance_W_per_K(scene.walls.size(), 0.0);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const double H = conductance_W_per_K[c];
    const auto i = std::size_t(contacts.pair[2 * c]);
    const std::int64_t j = contacts.pair[2 * c + 1];
    if (j >= 0) {
      out[c] = H * (temperature_K[i] - temperature_K[std::size_t(j)]);
      continue;
    }
    const auto w = std::size_t(-1 - j);
    const Wall& wall = scene.walls[w];
    if (wall.heat_flux_W_per_m2)
      flux_conductance_W_per_K[w] += H;
    else if (wall.temperature_K)
      out[c] = H * (temperature_K[i] - wall_T_K[w]);
  }
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const std::int64_t j = contacts.pair[2 * c + 1];
    if (j >= 0) continue;
    const auto w = std::size_t(-1 - j);
    const Wall& wall = scene.walls[w];
    if (!wall.heat_flux_W_per_m2 || !(flux_conductance_W_per_K[w] > 0.0)) continue;
    const double power_W = *wall.heat_flux_W_per_m2 * wall.heat_flux_area_m2;
    out[c] = -power_W * conductance_W_per_K[c] / flux_conductance_W_per_K[w];
  }
}

}  // namespace tmdem::coupling
