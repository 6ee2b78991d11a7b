#include "coupling/bridge/ThermalNetworkBuilder.h"

#include <cstdlib>
#include <limits>
#include <numbers>

#include "coupling/bridge/SceneToMechanics.h"

namespace tmdem::coupling {

ThermalNetworkBuilder::ThermalNetworkBuilder(const Scene& scene)
    : scene_(scene), law_(thermal::conductance_law_from_name(scene.thermal.conductance)) {}

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
  return net;
}

thermal::ContactBody ThermalNetworkBuilder::body(std::int64_t id) const {
  thermal::ContactBody b;
  int material = 0;
  if (id >= 0) {
    b.radius_m = scene_.particles[std::size_t(id)].radius_m;
    material = scene_.particles[std::size_t(id)].material;
  } else {
    b.radius_m = std::numeric_limits<double>::infinity();
    material = scene_.walls[std::size_t(-1 - id)].material;
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
  const bool conduction = scene_.effects.conduction;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    const bool isothermal_wall = j < 0 && scene_.walls[std::size_t(-1 - j)].temperature_K.has_value();
    const bool carries_heat = conduction && (j >= 0 || isothermal_wall);
    const bool open = is_active && !(*is_active)[c];
    const double H =
        carries_heat && !open ? conductance_W_per_K(i, j, contacts.normal_force_N[c]) : 0.0;
    contacts.conductance_W_per_K[c] = H;
    if (!carries_heat) continue;
    if (j >= 0)
      edges.add_edge(std::int32_t(i), std::int32_t(j), H);
    else
      edges.add_wall_edge(std::int32_t(i), *scene_.walls[std::size_t(-1 - j)].temperature_K, H);
  }
}

std::vector<std::string> ThermalNetworkBuilder::mode_names() const {
  std::vector<std::string> names;
  if (scene_.effects.conduction) {
    names.push_back("contact_conduction");
    for (const auto& w : scene_.walls)
      if (w.temperature_K) {
        names.push_back("wall_conduction");
        break;
      }
  }
  if (scene_.effects.convection) names.push_back("convection");
  if (scene_.effects.radiation) names.push_back("radiation");
  for (const auto& p : scene_.particles)
    if (p.heat_source_W != 0.0) {
      names.push_back("heat_source");
      break;
    }
  if (std::getenv("TMDEM_FAULT_AFTER_RHS_EVALS")) names.push_back("fault_injection");
  return names;
}

thermal::ModeSettings ThermalNetworkBuilder::mode_settings() const {
  thermal::ModeSettings s;
  s.convection_coefficient_W_per_m2K = scene_.convection.coefficient_W_per_m2K;
  s.fluid_temperature_K = scene_.convection.fluid_temperature_K;
  s.ambient_temperature_K = scene_.radiation.ambient_temperature_K;
  if (const char* n = std::getenv("TMDEM_FAULT_AFTER_RHS_EVALS")) s.fault_after_evaluations = std::atol(n);
  return s;
}

}  // namespace tmdem::coupling
