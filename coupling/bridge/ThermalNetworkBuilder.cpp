#include "coupling/bridge/ThermalNetworkBuilder.h"

#include <algorithm>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>

#include "coupling/bridge/LineOfSight.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/scene/HeatModes.h"
#include "mechanics/model/PairIndex.h"
#include "mechanics/detection/TouchingPairs.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/modes/ParticleResistance.h"

namespace tmdem::coupling {

namespace {

// The gas in the micro-gaps of rough contacts (thermal.conductance = "bahrami"): the [fluid] of
// effects.gas_conduction when it is on, its jump M from the same keys as the gas mode's macro-gap;
// with the gas off the contacts are in vacuum and nothing of the gas is read.
thermal::ContactGas contact_gas(const Scene& scene) {
  const auto* gas = thermal::find_heat_transfer_mode("gas_conduction");
  if (gas == nullptr || !mode_enabled(scene, *gas)) return {};
  const auto p = thermal::resolve_mode_parameters(*gas, scene.heat_modes);
  return {p["conductivity"],
          thermal::gas_parameter_m(p["pressure"], p["mean_free_path"], p["accommodation"],
                                   p["accommodation"], p["heat_capacity_ratio"], p["prandtl"])};
}

}  // namespace

ThermalNetworkBuilder::ThermalNetworkBuilder(const Scene& scene)
    : scene_(scene),
      law_(scene.thermal.conductance),
      contact_gas_(law_ == thermal::ConductanceLawKind::Bahrami ? contact_gas(scene)
                                                                 : thermal::ContactGas{}),
      contacts_carry_heat_(contacts_carry_heat(scene.effects)),
      near_reach_(near_pair_reach(scene)),
      line_of_sight_(needs_line_of_sight(scene)),
      temperature_dependent_(std::any_of(scene.materials.begin(), scene.materials.end(),
                                         [](const Material& m) { return m.temperature_dependent(); })) {
  std::int32_t tables = 0, fluxes = 0;
  for (const auto& w : scene.walls) {
    wall_table_.push_back(w.temperature_table.empty() ? -1 : tables++);
    wall_flux_.push_back(w.heat_flux_W_per_m2 ? fluxes++ : -1);
  }
}

thermal::ThermalNetwork ThermalNetworkBuilder::nodes() const {
  thermal::ThermalNetwork net;
  const std::size_t n = scene_.particles.size();
  net.resize_nodes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = scene_.particles[i];
    const auto& m = scene_.materials[p.material];
    net.heat_capacity_J_per_K[i] = particle_mass_kg(scene_, i) * m.heat_capacity_J_per_kgK;
    net.surface_area_m2[i] = 4.0 * std::numbers::pi * p.radius_m * p.radius_m;
    net.radius_m[i] = p.radius_m;
    net.emissivity[i] = m.emissivity;
    net.heat_source_W[i] = p.heat_source_W;
    net.held[i] = p.fixed_temperature ? 1 : 0;
  }
  if (temperature_dependent_) add_material_tables(net);
  // The particle's own resistance: each shell per unit solid angle (the scene refuses it with
  // conductivity tables; ThermalNetwork::validate refuses it with a k(T) contact law).
  if (scene_.thermal.particle_resistance != thermal::ParticleResistanceKind::Off) {
    net.gas_shells_per_ray =
        scene_.thermal.particle_resistance == thermal::ParticleResistanceKind::IsothermalCoreRays;
    net.shell_resistance_K_sr_per_W.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = scene_.particles[i];
      net.shell_resistance_K_sr_per_W[i] = thermal::shell_resistance_K_sr_per_W(
          p.radius_m, scene_.materials[p.material].conductivity_W_per_mK,
          scene_.thermal.core_fraction);
    }
  }
  for (const auto& w : scene_.walls) {
    net.isothermal_walls += w.temperature_K.has_value();
    if (!w.temperature_table.empty()) {
      thermal::PiecewiseLinearTable table;
      points_to_table(w.temperature_table, table);
      net.wall_temperature_tables.push_back(std::move(table));
    }
    if (w.heat_flux_W_per_m2) net.flux_wall_power_W.push_back(*w.heat_flux_W_per_m2 * w.heat_flux_area_m2);
  }
  return net;
}

void ThermalNetworkBuilder::add_material_tables(thermal::ThermalNetwork& net) const {
  auto table_of = [](const std::vector<std::array<double, 2>>& points, double constant) {
    thermal::PiecewiseLinearTable table;
    if (points.empty()) points_to_table({{1.0, constant}}, table);
    else points_to_table(points, table);
    return table;
  };
  for (const auto& m : scene_.materials) {
    net.material_conductivity.push_back(table_of(m.conductivity_table, m.conductivity_W_per_mK));
    net.material_specific_heat.push_back(table_of(m.heat_capacity_table, m.heat_capacity_J_per_kgK));
  }
  for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
    const auto& p = scene_.particles[i];
    net.node_material.push_back(p.material);
    net.mass_kg.push_back(particle_mass_kg(scene_, i));
    // The constant C_i the result file reports: C at the initial temperature.
    net.heat_capacity_J_per_K[i] = net.heat_capacity_at(i, p.temperature_K);
  }
  // The Hertz law carries k; the constant law does not depend on it.
  net.conductance_follows_conductivity = law_ == thermal::ConductanceLawKind::Hertz;
}

void ThermalNetworkBuilder::points_to_table(const std::vector<std::array<double, 2>>& points,
                                            thermal::PiecewiseLinearTable& table) {
  for (const auto& [x, y] : points) {
    table.x.push_back(x);
    table.y.push_back(y);
  }
}

thermal::ContactBody ThermalNetworkBuilder::body(std::int64_t id) const {
  thermal::ContactBody b;
  int material = 0;
  if (!mechanics::is_wall(id)) {
    b.radius_m = scene_.particles[std::size_t(id)].radius_m;
    material = scene_.particles[std::size_t(id)].material;
  } else {
    b.radius_m = std::numeric_limits<double>::infinity();
    material = scene_.walls[mechanics::wall_index(id)].material;
  }
  const auto& m = scene_.materials[std::size_t(material)];
  b.conductivity_W_per_mK = m.conductivity_W_per_mK;
  b.young_modulus_Pa = m.young_modulus_Pa;
  b.poisson_ratio = m.poisson_ratio;
  b.roughness_m = m.roughness_m;
  b.asperity_slope = m.asperity_slope;
  b.microhardness_Pa = m.microhardness_Pa;
  return b;
}

double ThermalNetworkBuilder::conductance_W_per_K(std::int64_t i, std::int64_t j,
                                                  double normal_force_N) const {
  if (law_ == thermal::ConductanceLawKind::Constant)
    return scene_.thermal.constant_conductance_W_per_K;
  if (law_ == thermal::ConductanceLawKind::Bahrami)
    return thermal::rough_contact_conductance_W_per_K(body(i), body(j), normal_force_N, contact_gas_);
  return thermal::hertz_conductance_W_per_K(body(i), body(j), normal_force_N,
                                            scene_.thermal.contact_flattening);
}

void ThermalNetworkBuilder::build_edges(ContactList& contacts, thermal::ThermalNetwork& edges,
                                        const std::vector<std::uint8_t>* is_active,
                                        const mechanics::ParticleSet* geometry) const {
  if (near_reach_ > 0.0) {
    if (geometry == nullptr || is_active != nullptr)
      throw std::logic_error(
          "ThermalNetworkBuilder: a mode working across gaps needs the frozen packing's geometry");
    build_edges_with_gaps(contacts, edges, *geometry);
    return;
  }
  edges.clear_edges();
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    const auto wall = mechanics::is_wall(j) ? mechanics::wall_index(j) : 0;
    const bool isothermal_wall =
        mechanics::is_wall(j) && scene_.walls[wall].temperature_K.has_value();
    const bool flux_wall = mechanics::is_wall(j) && wall_flux_[wall] >= 0;
    const bool carries_heat =
        contacts_carry_heat_ && (!mechanics::is_wall(j) || isothermal_wall || flux_wall);
    const bool open = is_active && !(*is_active)[c];
    const double H =
        carries_heat && !open ? conductance_W_per_K(i, j, contacts.normal_force_N[c]) : 0.0;
    contacts.conductance_W_per_K[c] = H;
    if (!carries_heat) continue;
    if (!mechanics::is_wall(j))
      edges.add_edge(std::int32_t(i), std::int32_t(j), H);
    else if (flux_wall)
      edges.add_flux_edge(std::int32_t(i), wall_flux_[wall], H);
    else
      add_wall_edge(edges, i, wall, H);
  }
}

void ThermalNetworkBuilder::add_gap_edge(thermal::ThermalNetwork& edges, std::int64_t i,
                                         std::int64_t j, double H, double force_N, bool contact,
                                         const mechanics::ParticleSet& geometry,
                                         const std::vector<mechanics::Wall>& walls) const {
  const auto& x = geometry.position;
  const auto& r = geometry.radius;
  // The gas sees the same solid disc as the contact conductance (flattened or not).
  const double a = contact ? thermal::hertz_contact_radius_m(body(i), body(j), force_N,
                                                             scene_.thermal.contact_flattening)
                           : 0.0;
  const auto si = std::size_t(i);
  if (!mechanics::is_wall(j)) {
    const double gap = geometry.branch(si, std::size_t(j)).norm() - r[si] - r[std::size_t(j)];
    edges.add_edge(std::int32_t(i), std::int32_t(j), H, gap, a, contact);
    return;
  }
  const auto w = mechanics::wall_index(j);
  if (wall_flux_[w] >= 0) {
    if (contacts_carry_heat_) edges.add_flux_edge(std::int32_t(i), wall_flux_[w], H);
  } else if (scene_.walls[w].temperature_K) {
    const double gap = walls[w].signed_distance(x[si]) - r[si];
    add_wall_edge(edges, i, w, H, gap, a, contact);
  }
}

void ThermalNetworkBuilder::add_wall_edge(thermal::ThermalNetwork& edges, std::int64_t i,
                                          std::size_t wall, double H, double gap_m,
                                          double contact_radius_m, bool contact) const {
  edges.add_wall_edge(std::int32_t(i), *scene_.walls[wall].temperature_K, H, wall_table_[wall],
                      gap_m, contact_radius_m, contact);
  if (temperature_dependent_) edges.wall_material.push_back(scene_.walls[wall].material);
  edges.wall_emissivity.push_back(scene_.materials[std::size_t(scene_.walls[wall].material)].emissivity);
}

bool ThermalNetworkBuilder::contact_carries_heat(std::int64_t j) const {
  if (!contacts_carry_heat_) return false;
  if (!mechanics::is_wall(j)) return true;
  const auto w = mechanics::wall_index(j);
  return wall_flux_[w] >= 0 || scene_.walls[w].temperature_K.has_value();
}

void ThermalNetworkBuilder::build_edges_with_gaps(ContactList& contacts,
                                                  thermal::ThermalNetwork& edges,
                                                  const mechanics::ParticleSet& geometry) const {
  edges.clear_edges();
  const auto walls = make_mechanics_walls(scene_);
  std::set<std::pair<std::int64_t, std::int64_t>> contact_pairs;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    contact_pairs.emplace(i, j);
    const double F = contacts.normal_force_N[c];
    const double H = contact_carries_heat(j) ? conductance_W_per_K(i, j, F) : 0.0;
    contacts.conductance_W_per_K[c] = H;
    add_gap_edge(edges, i, j, H, F, true, geometry, walls);
  }
  // Gas and radiation reach isothermal walls only (a flux wall's power goes to its contacts).
  for (const auto& p : mechanics::find_touching_pairs(geometry, walls, near_reach_))
    if (!contact_pairs.count({p.i, p.j}) &&
        (!mechanics::is_wall(p.j) || scene_.walls[mechanics::wall_index(p.j)].temperature_K))
      add_gap_edge(edges, p.i, p.j, 0.0, 0.0, false, geometry, walls);
  if (line_of_sight_) edges.edge_shadowed = shadowed_edges(edges, geometry);
}

void ThermalNetworkBuilder::add_near_pairs(const ContactList& contacts,
                                           const mechanics::ParticleSet& geometry,
                                           ContactList& out) const {
  out.clear();
  const auto near = mechanics::find_touching_pairs(geometry, make_mechanics_walls(scene_), near_reach_);
  std::vector<std::pair<std::int64_t, std::int64_t>> extra;
  for (const auto& p : near)
    if (!mechanics::is_wall(p.j) || scene_.walls[mechanics::wall_index(p.j)].temperature_K)
      extra.emplace_back(p.i, p.j);
  std::sort(extra.begin(), extra.end());
  // Merge walk: contacts keep their force and tangential force, near pairs get 0.
  std::size_t e = 0;
  for (std::size_t c = 0; c <= contacts.size(); ++c) {
    const bool more = c < contacts.size();
    const std::pair key = more ? std::pair(contacts.pair[2 * c], contacts.pair[2 * c + 1])
                               : std::pair(std::numeric_limits<std::int64_t>::max(), std::int64_t(0));
    for (; e < extra.size() && extra[e] < key; ++e) out.add(extra[e].first, extra[e].second, 0.0);
    if (e < extra.size() && extra[e] == key) ++e;
    if (!more) break;
    const auto* t = &contacts.tangential_force_N[3 * c];
    out.add(key.first, key.second, contacts.normal_force_N[c], {t[0], t[1], t[2]});
  }
}

void ThermalNetworkBuilder::build_pattern_edges(ContactList& pattern, const ContactList& active,
                                                thermal::ThermalNetwork& edges,
                                                const mechanics::ParticleSet& geometry) const {
  edges.clear_edges();
  const auto walls = make_mechanics_walls(scene_);
  std::size_t c = 0;  // merge walk over the active contacts
  for (std::size_t p = 0; p < pattern.size(); ++p) {
    const auto i = pattern.pair[2 * p], j = pattern.pair[2 * p + 1];
    const std::pair key(i, j);
    while (c < active.size() && std::pair(active.pair[2 * c], active.pair[2 * c + 1]) < key) ++c;
    const bool contact = c < active.size() && std::pair(active.pair[2 * c], active.pair[2 * c + 1]) == key;
    const double F = contact ? active.normal_force_N[c] : 0.0;
    const double H = contact && contact_carries_heat(j) ? conductance_W_per_K(i, j, F) : 0.0;
    pattern.conductance_W_per_K[p] = H;
    add_gap_edge(edges, i, j, H, F, contact, geometry, walls);
  }
  if (line_of_sight_) edges.edge_shadowed = shadowed_edges(edges, geometry);
}

std::vector<std::string> ThermalNetworkBuilder::mode_names(
    const thermal::ThermalNetwork& nodes) const {
  std::vector<std::string> names;
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode_enabled(scene_, *mode) && (mode->in_use == nullptr || mode->in_use(nodes)))
      names.emplace_back(mode->name);
  return names;
}

const thermal::ModeSettings& ThermalNetworkBuilder::mode_settings() const {
  return scene_.heat_modes;
}

}  // namespace tmdem::coupling
