#pragma once
// The thermal network: one node per particle, edges for particle-particle contacts and for
// particle-wall contacts with isothermal walls. Independent of mechanics: coupling fills it.
// Structure-of-arrays so the right-hand side and the Jacobian run over flat vectors.
#include <cstdint>
#include <vector>

#include "thermal/network/PiecewiseLinearTable.h"

namespace tmdem::thermal {

struct ThermalNetwork {
  // Nodes. (A new per-node array must also be picked for a process's piece in
  // extract_local_network, LocalNetwork.cpp, the heating over MPI.)
  std::vector<double> heat_capacity_J_per_K;   // C_i = m_i c_i
  std::vector<double> surface_area_m2;         // 4 pi r^2, for convection and radiation
  std::vector<double> radius_m;                // r_i, for the gap-dependent modes (gas, pair radiation)
  std::vector<double> emissivity;              // 0..1
  std::vector<double> heat_source_W;           // imposed power P_i
  std::vector<std::uint8_t> held;              // 1: temperature held for the whole run
  // Walls held at a temperature, touching a particle now or not: wall edges come and go with
  // the contacts, but whether wall conduction can ever matter is known from the start.
  std::size_t isothermal_walls = 0;

  // Particle-particle edges (a != b; each unordered pair at most once): the contacts, plus the
  // near pairs (contact conductance 0) when a switched-on mode works across gaps.
  std::vector<std::int32_t> edge_a, edge_b;
  std::vector<double> edge_conductance_W_per_K;
  std::vector<double> edge_gap_m;             // surface gap |x_a - x_b| - r_a - r_b; < 0 overlap
  std::vector<double> edge_contact_radius_m;  // Hertz contact radius (0: no force, or near pair)
  std::vector<std::uint8_t> edge_in_contact;  // 1: a contact of the mechanics (or geometry)
  // 1: a third particle crosses the line between the pair's centres (pair radiation does not
  // pass). Filled only for a mode that needs it (ModeDescription::needs_line_of_sight); empty:
  // every pair sees the other.
  std::vector<std::uint8_t> edge_shadowed;

  // Particle-wall edges, isothermal walls only (adiabatic walls carry no heat, so no edge).
  std::vector<std::int32_t> wall_node;
  std::vector<double> wall_temperature_K;
  std::vector<double> wall_conductance_W_per_K;
  std::vector<double> wall_gap_m;             // signed distance to the plane - r
  std::vector<double> wall_contact_radius_m;
  std::vector<std::uint8_t> wall_in_contact;
  // The wall's emissivity, 0..1, per wall edge (pair radiation with walls). Empty: the walls
  // exchange no radiation (networks filled by hand).
  std::vector<double> wall_emissivity;
  // Wall temperatures that follow a table in time (K against s, piecewise linear, clamped):
  // per wall edge the table's index, -1 for a constant wall. apply_time writes the tables'
  // values at t into wall_temperature_K.
  std::vector<PiecewiseLinearTable> wall_temperature_tables;  // node data: set once
  std::vector<std::int32_t> wall_schedule;                    // per wall edge

  // Walls with an imposed heat flux: each wall's power (flux x its area, W) is shared among
  // the particles touching it in proportion to their contact conductance.
  std::vector<double> flux_wall_power_W;                      // node data: one per flux wall
  std::vector<std::int32_t> flux_node, flux_wall;             // per flux edge
  std::vector<double> flux_conductance_W_per_K;               // per flux edge

  // Temperature-dependent materials (docs/heat-modes.md "Temperature-dependent properties"): empty unless
  // some material gives its conductivity or heat capacity as a table [[T, value], ...]. Then
  // every material has both tables (a constant is a one-point table), C_i(T) = m_i c(T_i), the
  // thermal energy is sum m_i int_0^T_i c, and, with conductance_follows_conductivity, each
  // contact's H carries k(T) by the Kirchhoff form (thermal/modes/KirchhoffContactFlow.h).
  std::vector<PiecewiseLinearTable> material_conductivity;   // k(T), W/(m K) against K
  std::vector<PiecewiseLinearTable> material_specific_heat;  // c(T), J/(kg K) against K
  std::vector<std::int32_t> node_material;                   // per node
  std::vector<double> mass_kg;                               // per node
  std::vector<std::int32_t> wall_material;                   // per wall edge
  // The contact law is Hertz (H = 2 a k_h): edge_conductance_W_per_K and
  // wall_conductance_W_per_K hold H at the reference conductivities (each table's first value),
  // from which the modes take 2 a = H / k_h(reference).
  bool conductance_follows_conductivity = false;

  // The particle's own thermal resistance (docs/heat-modes.md "The particle's own resistance"):
  // empty when thermal.particle_resistance = "off". Per node, the resistance of
  // its solid shell between the isothermal core (radius c r) and the surface per unit solid
  // angle, (1/(c r) - 1/r) / k, K sr/W. Node data; needs constant conductivities.
  std::vector<double> shell_resistance_K_sr_per_W;
  // "isothermal_core_rays": the gas modes integrate the shells ray by ray with the gas
  // (GasGap::shell_gap_a_m) and stay out of the lumped series factors below, which then hold
  // the contact paths alone.
  bool gas_shells_per_ray = false;
  // Derived from the above and the modes' pair conductances by thermal::update_series_factors
  // (ThermalSystem calls it whenever the edges change): per particle edge and per isothermal-wall
  // edge, the factor H'/H = 1 / (1 + H_pair (R_a + R_b)) that puts the particles' shells in
  // series with the summed conductance H_pair of every mode on that pair. Empty: factor 1.
  std::vector<double> edge_series_factor, wall_series_factor;
  double edge_factor(std::size_t e) const {
    return edge_series_factor.empty() ? 1.0 : edge_series_factor[e];
  }
  double wall_factor(std::size_t w) const {
    return wall_series_factor.empty() ? 1.0 : wall_series_factor[w];
  }

  // Mechanical power dissipated at the contacts over the current mechanical step (W; slip work
  // plus impact loss, mechanics' -r . u_theta / h), one entry per contact of a moving packing:
  // particle a, and particle b or -1 for a wall. Replaced every step like the edges; read by
  // the modes that turn it into heat (ModeDescription::uses_contact_dissipation).
  std::vector<std::int32_t> dissipation_a, dissipation_b;
  std::vector<double> dissipation_W;

  std::size_t node_count() const { return heat_capacity_J_per_K.size(); }
  bool temperature_dependent() const { return !node_material.empty(); }
  // C_i(T) (J/K), dC_i/dT (J/K^2) and int_0^T C_i (J): from the tables when temperature
  // dependent, else heat_capacity_J_per_K[i] (slope 0, energy C_i T).
  double heat_capacity_at(std::size_t i, double T_K) const;
  double heat_capacity_slope_at(std::size_t i, double T_K) const;
  double thermal_energy_at(std::size_t i, double T_K) const;
  // The inverse of thermal_energy_at: T_i at energy E_J (temperature-dependent networks).
  double temperature_at_energy(std::size_t i, double E_J) const;
  std::size_t edge_count() const { return edge_a.size(); }
  std::size_t wall_edge_count() const { return wall_node.size(); }
  std::size_t flux_edge_count() const { return flux_node.size(); }

  // Sizes every node array for n nodes (zero sources, emissivity, nothing held).
  void resize_nodes(std::size_t n);
  void clear_edges();
  void clear_wall_edges();  // the isothermal-wall edges only (flux edges stay)
  // Geometry defaults: a touching contact (gap 0) of unknown contact radius (0).
  void add_edge(std::int32_t a, std::int32_t b, double conductance_W_per_K, double gap_m = 0.0,
                double contact_radius_m = 0.0, bool in_contact = true);
  // schedule: index into wall_temperature_tables, -1 for a constant wall_temperature_K.
  void add_wall_edge(std::int32_t node, double wall_temperature_K, double conductance_W_per_K,
                     std::int32_t schedule = -1, double gap_m = 0.0,
                     double contact_radius_m = 0.0, bool in_contact = true);
  void add_flux_edge(std::int32_t node, std::int32_t flux_wall_index, double conductance_W_per_K);
  // b = -1: a contact with a wall.
  void add_dissipation(std::int32_t a, std::int32_t b, double power_W);
  // Wall temperatures of the scheduled wall edges at time t_s.
  void apply_time(double t_s);
  // Throws std::invalid_argument naming the first inconsistency (sizes, ids, non-finite or
  // negative conductance, non-positive heat capacity).
  void validate() const;
  // True when the particle-particle edges are the same pairs, in the same order, as other's:
  // then only values changed and the sparsity pattern can be kept.
  bool same_edges_as(const ThermalNetwork& other) const;
};

}  // namespace tmdem::thermal
