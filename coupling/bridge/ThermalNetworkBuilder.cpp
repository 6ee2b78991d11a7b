#include "coupling/bridge/ThermalNetworkBuilder.h"

#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/scene/HeatModes.h"
#include "mechanics/PairIndex.h"
#include "mechanics/TouchingPairs.h"
#include "thermal/ModeRegistry.h"

namespace tmdem::coupling {

ThermalNetworkBuilder::ThermalNetworkBuilder(const Scene& scene)
    : scene_(scene),
      law_(thermal::conductance_law_from_name(scene.thermal.conductance)),
      contacts_carry_heat_(contacts_carry_heat(scene.effects)),
      near_reach_(near_pair_reach(scene)) {
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
  for (const auto& w : scene_.walls) {
    net.isothermal_walls += w.temperature_K.has_value();
    if (!w.temperature_table.empty()) {
      thermal::PiecewiseLinearTable table;
      for (const auto& [t, T] : w.temperature_table) {
        table.x.push_back(t);
        table.y.push_back(T);
      }
      net.wall_temperature_tables.push_back(std::move(table));
    }
    if (w.heat_flux_W_per_m2) net.flux_wall_power_W.push_back(*w.heat_flux_W_per_m2 * w.heat_flux_area_m2);
  }
  return net;
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
  return b;
}

double ThermalNetworkBuilder::conductance_W_per_K(std::int64_t i, std::int64_t j,
                                                  double normal_force_N) const {
  if (law_ == thermal::ConductanceLawKind::Constant)
    return scene_.thermal.constant_conductance_W_per_K;
  return thermal::hertz_conductance_W_per_K(body(i), body(j), normal_force_N);
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
      edges.add_wall_edge(std::int32_t(i), *scene_.walls[wall].temperature_K, H, wall_table_[wall]);
  }
}

void ThermalNetworkBuilder::build_edges_with_gaps(ContactList& contacts,
                                                  thermal::ThermalNetwork& edges,
                                                  const mechanics::ParticleSet& geometry) const {
  edges.clear_edges();
  const auto walls = make_mechanics_walls(scene_);
  const auto& x = geometry.position;
  const auto& r = geometry.radius;
  const auto isothermal = [&](std::int64_t j) {
    return scene_.walls[mechanics::wall_index(j)].temperature_K.has_value();
  };
  std::set<std::pair<std::int64_t, std::int64_t>> contact_pairs;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    contact_pairs.emplace(i, j);
    const bool wall = mechanics::is_wall(j);
    const auto w = wall ? mechanics::wall_index(j) : 0;
    const bool flux_wall = wall && wall_flux_[w] >= 0;
    const double F = contacts.normal_force_N[c];
    const bool carries_heat = contacts_carry_heat_ && (!wall || isothermal(j) || flux_wall);
    const double H = carries_heat ? conductance_W_per_K(i, j, F) : 0.0;
    contacts.conductance_W_per_K[c] = H;
    const double a = thermal::hertz_contact_radius_m(body(i), body(j), F);
    const auto si = std::size_t(i);
    if (!wall) {
      const double gap = (x[si] - x[std::size_t(j)]).norm() - r[si] - r[std::size_t(j)];
      edges.add_edge(std::int32_t(i), std::int32_t(j), H, gap, a, true);
    } else if (flux_wall) {
      if (carries_heat) edges.add_flux_edge(std::int32_t(i), wall_flux_[w], H);
    } else if (isothermal(j)) {
      const double gap = walls[w].signed_distance(x[si]) - r[si];
      edges.add_wall_edge(std::int32_t(i), *scene_.walls[w].temperature_K, H, wall_table_[w], gap,
                          a, true);
    }
  }
  // Gas and radiation reach isothermal walls only (a flux wall's power goes to its contacts).
  for (const auto& p : mechanics::find_touching_pairs(geometry, walls, near_reach_)) {
    if (contact_pairs.count({p.i, p.j})) continue;
    if (!mechanics::is_wall(p.j)) {
      edges.add_edge(std::int32_t(p.i), std::int32_t(p.j), 0.0, p.gap_m, 0.0, false);
    } else if (isothermal(p.j)) {
      const auto w = mechanics::wall_index(p.j);
      edges.add_wall_edge(std::int32_t(p.i), *scene_.walls[w].temperature_K, 0.0, wall_table_[w],
                          p.gap_m, 0.0, false);
    }
  }
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
