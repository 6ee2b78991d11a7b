#include "coupling/bridge/ThermalNetworkBuilder.h"

#include <limits>
#include <numbers>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/scene/HeatModes.h"
#include "mechanics/PairIndex.h"
#include "thermal/ModeRegistry.h"

namespace tmdem::coupling {

ThermalNetworkBuilder::ThermalNetworkBuilder(const Scene& scene)
    : scene_(scene),
      law_(thermal::conductance_law_from_name(scene.thermal.conductance)),
      contacts_carry_heat_(contacts_carry_heat(scene.effects)) {
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
                                        const std::vector<std::uint8_t>* is_active) const {
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

std::vector<std::string> ThermalNetworkBuilder::mode_names(
    const thermal::ThermalNetwork& nodes) const {
  std::vector<std::string> names;
  for (const auto* mode : thermal::heat_transfer_modes())
    if (switched_on(scene_.effects, *mode) && (mode->in_use == nullptr || mode->in_use(nodes)))
      names.emplace_back(mode->name);
  return names;
}

const thermal::ModeSettings& ThermalNetworkBuilder::mode_settings() const {
  return scene_.heat_modes;
}

}  // namespace tmdem::coupling
