#include "thermal/network/ThermalNetwork.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

void ThermalNetwork::resize_nodes(std::size_t n) {
  heat_capacity_J_per_K.assign(n, 0.0);
  surface_area_m2.assign(n, 0.0);
  radius_m.assign(n, 0.0);
  emissivity.assign(n, 0.0);
  heat_source_W.assign(n, 0.0);
  held.assign(n, 0);
}

void ThermalNetwork::clear_edges() {
  edge_a.clear();
  edge_b.clear();
  edge_conductance_W_per_K.clear();
  edge_gap_m.clear();
  edge_contact_radius_m.clear();
  edge_in_contact.clear();
  edge_shadowed.clear();
  edge_series_factor.clear();
  clear_wall_edges();
  flux_node.clear();
  flux_wall.clear();
  flux_conductance_W_per_K.clear();
  dissipation_a.clear();
  dissipation_b.clear();
  dissipation_W.clear();
}

void ThermalNetwork::clear_wall_edges() {
  wall_node.clear();
  wall_material.clear();
  wall_temperature_K.clear();
  wall_conductance_W_per_K.clear();
  wall_schedule.clear();
  wall_gap_m.clear();
  wall_contact_radius_m.clear();
  wall_in_contact.clear();
  wall_emissivity.clear();
  wall_series_factor.clear();
}

void ThermalNetwork::add_edge(std::int32_t a, std::int32_t b, double conductance_W_per_K,
                              double gap_m, double contact_radius_m, bool in_contact) {
  edge_a.push_back(a);
  edge_b.push_back(b);
  edge_conductance_W_per_K.push_back(conductance_W_per_K);
  edge_gap_m.push_back(gap_m);
  edge_contact_radius_m.push_back(contact_radius_m);
  edge_in_contact.push_back(in_contact ? 1 : 0);
}

void ThermalNetwork::add_wall_edge(std::int32_t node, double temperature_K,
                                   double conductance_W_per_K, std::int32_t schedule,
                                   double gap_m, double contact_radius_m, bool in_contact) {
  wall_node.push_back(node);
  wall_temperature_K.push_back(temperature_K);
  wall_conductance_W_per_K.push_back(conductance_W_per_K);
  wall_schedule.push_back(schedule);
  wall_gap_m.push_back(gap_m);
  wall_contact_radius_m.push_back(contact_radius_m);
  wall_in_contact.push_back(in_contact ? 1 : 0);
}

void ThermalNetwork::add_flux_edge(std::int32_t node, std::int32_t flux_wall_index,
                                   double conductance_W_per_K) {
  flux_node.push_back(node);
  flux_wall.push_back(flux_wall_index);
  flux_conductance_W_per_K.push_back(conductance_W_per_K);
}

double ThermalNetwork::heat_capacity_at(std::size_t i, double T) const {
  if (!temperature_dependent()) return heat_capacity_J_per_K[i];
  return mass_kg[i] * material_specific_heat[std::size_t(node_material[i])](T);
}

double ThermalNetwork::heat_capacity_slope_at(std::size_t i, double T) const {
  if (!temperature_dependent()) return 0.0;
  return mass_kg[i] * material_specific_heat[std::size_t(node_material[i])].slope(T);
}

double ThermalNetwork::thermal_energy_at(std::size_t i, double T) const {
  if (!temperature_dependent()) return heat_capacity_J_per_K[i] * T;
  return mass_kg[i] * material_specific_heat[std::size_t(node_material[i])].integral(T);
}

double ThermalNetwork::temperature_at_energy(std::size_t i, double E) const {
  if (!temperature_dependent()) return E / heat_capacity_J_per_K[i];
  return material_specific_heat[std::size_t(node_material[i])].inverse_integral(E / mass_kg[i]);
}

void ThermalNetwork::add_dissipation(std::int32_t a, std::int32_t b, double power_W) {
  dissipation_a.push_back(a);
  dissipation_b.push_back(b);
  dissipation_W.push_back(power_W);
}

void ThermalNetwork::apply_time(double t_s) {
  for (std::size_t w = 0; w < wall_schedule.size(); ++w)
    if (wall_schedule[w] >= 0) wall_temperature_K[w] = wall_temperature_tables[std::size_t(wall_schedule[w])](t_s);
}

void ThermalNetwork::validate() const {
  const std::size_t n = node_count();
  auto fail = [](const std::string& what) { throw std::invalid_argument("thermal network: " + what); };
  if (surface_area_m2.size() != n || radius_m.size() != n || emissivity.size() != n ||
      heat_source_W.size() != n || held.size() != n)
    fail("node arrays have different sizes");
  for (std::size_t i = 0; i < n; ++i)
    if (!(heat_capacity_J_per_K[i] > 0.0) || !std::isfinite(heat_capacity_J_per_K[i]))
      fail("node " + std::to_string(i) + " has heat capacity " +
           std::to_string(heat_capacity_J_per_K[i]) + " J/K (must be positive and finite)");
  if (edge_b.size() != edge_a.size() || edge_conductance_W_per_K.size() != edge_a.size() ||
      edge_gap_m.size() != edge_a.size() || edge_contact_radius_m.size() != edge_a.size() ||
      edge_in_contact.size() != edge_a.size())
    fail("edge arrays have different sizes");
  for (std::size_t e = 0; e < edge_a.size(); ++e) {
    const auto a = edge_a[e], b = edge_b[e];
    if (a < 0 || b < 0 || std::size_t(a) >= n || std::size_t(b) >= n || a == b)
      fail("edge " + std::to_string(e) + " joins nodes " + std::to_string(a) + " and " +
           std::to_string(b) + " (need two distinct nodes below " + std::to_string(n) + ")");
    const double h = edge_conductance_W_per_K[e];
    if (!(h >= 0.0) || !std::isfinite(h))
      fail("edge " + std::to_string(e) + " has conductance " + std::to_string(h) + " W/K");
  }
  if (wall_temperature_K.size() != wall_node.size() ||
      wall_conductance_W_per_K.size() != wall_node.size() || wall_gap_m.size() != wall_node.size() ||
      wall_contact_radius_m.size() != wall_node.size() || wall_in_contact.size() != wall_node.size())
    fail("wall edge arrays have different sizes");
  for (std::size_t w = 0; w < wall_node.size(); ++w) {
    if (wall_node[w] < 0 || std::size_t(wall_node[w]) >= n)
      fail("wall edge " + std::to_string(w) + " names node " + std::to_string(wall_node[w]));
    const double h = wall_conductance_W_per_K[w];
    if (!(h >= 0.0) || !std::isfinite(h))
      fail("wall edge " + std::to_string(w) + " has conductance " + std::to_string(h) + " W/K");
  }
  // Networks filled by hand (tests) may leave the schedule empty: every wall is constant.
  if (!wall_schedule.empty() && wall_schedule.size() != wall_node.size())
    fail("wall schedule has " + std::to_string(wall_schedule.size()) + " entries for " +
         std::to_string(wall_node.size()) + " wall edges");
  for (std::size_t w = 0; w < wall_schedule.size(); ++w)
    if (wall_schedule[w] < -1 || wall_schedule[w] >= std::int32_t(wall_temperature_tables.size()))
      fail("wall edge " + std::to_string(w) + " names temperature table " +
           std::to_string(wall_schedule[w]) + " of " + std::to_string(wall_temperature_tables.size()));
  for (std::size_t k = 0; k < wall_temperature_tables.size(); ++k) {
    const auto& t = wall_temperature_tables[k];
    if (t.x.empty() || t.x.size() != t.y.size() || !std::is_sorted(t.x.begin(), t.x.end()))
      fail("wall temperature table " + std::to_string(k) + " is empty, uneven or unsorted");
  }
  if (flux_wall.size() != flux_node.size() || flux_conductance_W_per_K.size() != flux_node.size())
    fail("flux edge arrays have different sizes");
  for (std::size_t f = 0; f < flux_node.size(); ++f) {
    if (flux_node[f] < 0 || std::size_t(flux_node[f]) >= n || flux_wall[f] < 0 ||
        std::size_t(flux_wall[f]) >= flux_wall_power_W.size())
      fail("flux edge " + std::to_string(f) + " names node " + std::to_string(flux_node[f]) +
           " and flux wall " + std::to_string(flux_wall[f]));
    const double h = flux_conductance_W_per_K[f];
    if (!(h >= 0.0) || !std::isfinite(h))
      fail("flux edge " + std::to_string(f) + " has conductance " + std::to_string(h) + " W/K");
  }
  if (!shell_resistance_K_sr_per_W.empty()) {
    if (shell_resistance_K_sr_per_W.size() != n) fail("shell resistances are not one per node");
    for (std::size_t i = 0; i < n; ++i)
      if (!(shell_resistance_K_sr_per_W[i] >= 0.0) || !std::isfinite(shell_resistance_K_sr_per_W[i]))
        fail("node " + std::to_string(i) + " has shell resistance " +
             std::to_string(shell_resistance_K_sr_per_W[i]) + " K sr/W");
    if (conductance_follows_conductivity)
      fail("the particle's own resistance needs constant conductivities (the contact law "
           "follows k(T))");
  }
  if (gas_shells_per_ray && shell_resistance_K_sr_per_W.empty())
    fail("the gas's shells per ray need the shell resistances (particle_resistance is off)");
  if (!edge_shadowed.empty() && edge_shadowed.size() != edge_a.size())
    fail("edge shadow marks are not one per edge");
  if (!wall_emissivity.empty() && wall_emissivity.size() != wall_node.size())
    fail("wall emissivities are not one per wall edge");
  for (const double e : wall_emissivity)
    if (!(e >= 0.0 && e <= 1.0)) fail("a wall edge has emissivity " + std::to_string(e) + " (need 0..1)");
  if (!edge_series_factor.empty() && edge_series_factor.size() != edge_a.size())
    fail("edge series factors are not one per edge");
  if (!wall_series_factor.empty() && wall_series_factor.size() != wall_node.size())
    fail("wall series factors are not one per wall edge");
  if (temperature_dependent()) {
    const auto materials = material_conductivity.size();
    if (node_material.size() != n || mass_kg.size() != n || material_specific_heat.size() != materials)
      fail("temperature-dependent node arrays have different sizes");
    for (std::size_t i = 0; i < n; ++i)
      if (node_material[i] < 0 || std::size_t(node_material[i]) >= materials || !(mass_kg[i] > 0.0))
        fail("node " + std::to_string(i) + " names material " + std::to_string(node_material[i]) +
             " with mass " + std::to_string(mass_kg[i]) + " kg");
    for (const auto* tables : {&material_conductivity, &material_specific_heat})
      for (const auto& t : *tables)
        if (t.x.empty() || t.x.size() != t.y.size() || !std::is_sorted(t.x.begin(), t.x.end()) ||
            !(t.min_y() > 0.0))
          fail("a material property table is empty, uneven, unsorted or not positive");
    if (conductance_follows_conductivity && wall_material.size() != wall_node.size())
      fail("wall material has " + std::to_string(wall_material.size()) + " entries for " +
           std::to_string(wall_node.size()) + " wall edges");
    for (const auto m : wall_material)
      if (m < 0 || std::size_t(m) >= materials) fail("wall edge names material " + std::to_string(m));
  }
  if (dissipation_b.size() != dissipation_a.size() || dissipation_W.size() != dissipation_a.size())
    fail("dissipation arrays have different sizes");
  for (std::size_t k = 0; k < dissipation_a.size(); ++k) {
    const auto a = dissipation_a[k], b = dissipation_b[k];
    if (a < 0 || std::size_t(a) >= n || b < -1 || (b >= 0 && std::size_t(b) >= n) || a == b ||
        !std::isfinite(dissipation_W[k]))
      fail("dissipation " + std::to_string(k) + " joins nodes " + std::to_string(a) + " and " +
           std::to_string(b) + " with " + std::to_string(dissipation_W[k]) +
           " W (need node a below " + std::to_string(n) + ", b another node or -1, finite power)");
  }
}

bool ThermalNetwork::same_edges_as(const ThermalNetwork& other) const {
  return edge_a == other.edge_a && edge_b == other.edge_b && wall_node == other.wall_node;
}

}  // namespace tmdem::thermal
