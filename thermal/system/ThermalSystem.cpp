#include "thermal/system/ThermalSystem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "thermal/modes/ParticleResistance.h"
#include "thermal/network/NodeLoopThreads.h"

namespace tmdem::thermal {

ThermalSystem::ThermalSystem(ThermalNetwork network,
                             std::vector<std::unique_ptr<HeatTransferMode>> modes)
    : network_(std::move(network)), modes_(std::move(modes)) {
  network_.validate();
  network_.apply_time(time_s_);
  for (auto& mode : modes_) mode->update_geometry(network_);
  update_series_factors();
}

const JacobianPattern& ThermalSystem::pattern() const {
  if (!pattern_built_) {
    pattern_.build(network_);
    pattern_built_ = true;
  }
  return pattern_;
}

void ThermalSystem::update_series_factors() {
  std::vector<const HeatTransferMode*> modes;
  for (const auto& mode : modes_) modes.push_back(mode.get());
  thermal::update_series_factors(network_, modes);
}

bool ThermalSystem::symmetric_jacobian() const {
  // k(T) makes d q_a / d T_b differ from d q_b / d T_a, and C(T) the sqrt(C) scaling variable.
  if (network_.temperature_dependent()) return false;
  for (const auto& mode : modes_)
    if (!mode->symmetric_jacobian()) return false;
  return true;
}

void ThermalSystem::replace_edges(const ThermalNetwork& edges) {
  const bool same_shape = network_.same_edges_as(edges);
  network_.edge_a = edges.edge_a;
  network_.edge_b = edges.edge_b;
  network_.edge_conductance_W_per_K = edges.edge_conductance_W_per_K;
  network_.wall_node = edges.wall_node;
  network_.wall_temperature_K = edges.wall_temperature_K;
  network_.wall_conductance_W_per_K = edges.wall_conductance_W_per_K;
  network_.wall_schedule = edges.wall_schedule;
  network_.flux_node = edges.flux_node;
  network_.flux_wall = edges.flux_wall;
  network_.flux_conductance_W_per_K = edges.flux_conductance_W_per_K;
  network_.edge_gap_m = edges.edge_gap_m;
  network_.edge_contact_radius_m = edges.edge_contact_radius_m;
  network_.edge_in_contact = edges.edge_in_contact;
  network_.edge_shadowed = edges.edge_shadowed;
  network_.wall_gap_m = edges.wall_gap_m;
  network_.wall_contact_radius_m = edges.wall_contact_radius_m;
  network_.wall_in_contact = edges.wall_in_contact;
  network_.wall_material = edges.wall_material;
  network_.wall_emissivity = edges.wall_emissivity;
  network_.dissipation_a = edges.dissipation_a;
  network_.dissipation_b = edges.dissipation_b;
  network_.dissipation_W = edges.dissipation_W;
  network_.edge_series_factor.clear();  // derived from the new edges below
  network_.wall_series_factor.clear();
  network_.validate();
  network_.apply_time(time_s_);
  for (auto& mode : modes_) mode->update_geometry(network_);
  update_series_factors();
  if (same_shape) {
    ++values_version_;
  } else {
    pattern_ = JacobianPattern{};  // built again when next asked for
    pattern_built_ = false;
    ++topology_version_;
    ++values_version_;
  }
}

void ThermalSystem::set_time(double t_s) {
  time_s_ = t_s;
  network_.apply_time(t_s);
}

bool ThermalSystem::heat_flow(std::span<const double> T, std::span<double> q,
                              double& boundary_W) const {
  std::fill(q.begin(), q.end(), 0.0);
  boundary_W = 0.0;
  for (const auto& mode : modes_)
    if (!mode->add_heat_flow(network_, T, q, boundary_W)) return false;
  return true;
}

double ThermalSystem::dissipation_boundary_W() const {
  double boundary_W = 0.0;
  for (const auto& mode : modes_) {
    if (!mode->heats_from_dissipation()) continue;
    dissipation_scratch_W_.assign(network_.node_count(), 0.0);
    mode->add_heat_flow(network_, {}, dissipation_scratch_W_, boundary_W);  // T-independent
  }
  return boundary_W;
}

bool ThermalSystem::time_derivative(std::span<const double> T, std::span<double> dTdt,
                                    double& boundary_W) const {
  if (!heat_flow(T, dTdt, boundary_W)) return false;
  const auto& held = network_.held;
  const std::int64_t n = std::int64_t(dTdt.size());
#pragma omp parallel for schedule(static) num_threads(node_loop_threads(dTdt.size()))
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = std::size_t(k);
    dTdt[i] = held[i] ? 0.0 : dTdt[i] / network_.heat_capacity_at(i, T[i]);
  }
  return true;
}

void ThermalSystem::evaluate_jacobian(std::span<const double> T, JacobianEvaluation& J) const {
  J.diagonal_W_per_K.assign(network_.node_count(), 0.0);
  J.edge_W_per_K.assign(network_.edge_count(), 0.0);
  J.edge_ab_W_per_K.assign(network_.edge_count(), 0.0);
  J.edge_ba_W_per_K.assign(network_.edge_count(), 0.0);
  for (const auto& mode : modes_)
    mode->add_jacobian(network_, T,
                       JacobianView{J.diagonal_W_per_K, J.edge_W_per_K, J.edge_ab_W_per_K,
                                    J.edge_ba_W_per_K});
  J.capacity_J_per_K.clear();
  if (!network_.temperature_dependent()) return;
  // Rows divided by C_i(T_i) below. The capacity's own slope (-q_i C_i' / C_i^2 on the
  // diagonal) is left out on purpose: the implicit integrators then use the enthalpy E_i as
  // their state (SundialsIntegratorBase), whose Jacobian d q / d E = (d q / d T) C^-1 is exactly
  // diag(C) J diag(C)^-1 of this J.
  J.capacity_J_per_K.resize(size());
  for (std::size_t i = 0; i < size(); ++i) J.capacity_J_per_K[i] = network_.heat_capacity_at(i, T[i]);
}

double ThermalSystem::capacity(const JacobianEvaluation& J, std::size_t i) const {
  return J.capacity_J_per_K.empty() ? network_.heat_capacity_J_per_K[i] : J.capacity_J_per_K[i];
}

void ThermalSystem::check_evaluation(const JacobianEvaluation& J) const {
  if (J.diagonal_W_per_K.size() != size() || J.edge_W_per_K.size() != network_.edge_count() ||
      J.edge_ab_W_per_K.size() != network_.edge_count() ||
      J.edge_ba_W_per_K.size() != network_.edge_count())
    throw std::logic_error("ThermalSystem: Jacobian evaluated for another contact graph (" +
                           std::to_string(J.edge_W_per_K.size()) + " edges, network has " +
                           std::to_string(network_.edge_count()) + "); call evaluate_jacobian");
}

void ThermalSystem::jacobian_values(const JacobianEvaluation& J, std::span<double> values,
                                    std::span<const double> scale) const {
  check_evaluation(J);
  const auto& held = network_.held;
  const JacobianPattern& p = pattern();
  std::fill(values.begin(), values.end(), 0.0);
  for (std::size_t i = 0; i < size(); ++i)
    if (!held[i])
      values[p.diagonal_slot[i]] +=
          J.diagonal_W_per_K[i] / capacity(J, i);
  for (std::size_t e = 0; e < network_.edge_count(); ++e) {
    const auto a = network_.edge_a[e], b = network_.edge_b[e];
    if (held[a] || held[b]) continue;
    const double h_ab = J.edge_W_per_K[e] + J.edge_ab_W_per_K[e];
    const double h_ba = J.edge_W_per_K[e] + J.edge_ba_W_per_K[e];
    const double sab = scale.empty() ? 1.0 : scale[a] / scale[b];
    values[p.slot_ab[e]] += h_ab / capacity(J, std::size_t(a)) * sab;
    values[p.slot_ba[e]] += h_ba / capacity(J, std::size_t(b)) / sab;
  }
}

void ThermalSystem::jacobian_times(const JacobianEvaluation& J, std::span<const double> v,
                                   std::span<double> Jv, std::span<const double> scale) const {
  check_evaluation(J);
  const auto& held = network_.held;
  const auto* a = network_.edge_a.data();
  const auto* b = network_.edge_b.data();
  const JacobianPattern& p = pattern();  // before the threads: built here if need be
  const auto* start = p.node_edge_start.data();
  const auto* incident = p.node_edge.data();
  // Work in unscaled variables: u = S^-1 v, w = J u, Jv = S w. Row by row: each row adds its
  // diagonal, then its edges in edge order (JacobianPattern::node_edge), the order of a loop
  // over the edges, so every thread count gives the same bits.
  const auto u = [&](std::size_t k) { return scale.empty() ? v[k] : v[k] / scale[k]; };
  const std::int64_t n = std::int64_t(size());
#pragma omp parallel for schedule(static) num_threads(node_loop_threads(size()))
  for (std::int64_t row = 0; row < n; ++row) {
    const auto i = std::size_t(row);
    double w = held[i] ? 0.0 : J.diagonal_W_per_K[i] * u(i);
    for (auto k = start[i]; k < start[i + 1]; ++k) {
      const auto e = std::size_t(incident[k]);
      const auto ea = std::size_t(a[e]), eb = std::size_t(b[e]);
      if (held[ea] || held[eb]) continue;
      if (ea == i) w += (J.edge_W_per_K[e] + J.edge_ab_W_per_K[e]) * u(eb);
      if (eb == i) w += (J.edge_W_per_K[e] + J.edge_ba_W_per_K[e]) * u(ea);
    }
    Jv[i] = w * ((scale.empty() ? 1.0 : scale[i]) / capacity(J, i));
  }
}

double ThermalSystem::explicit_stability_bound_s(double T_max_K) const {
  const std::vector<double> T(size(), T_max_K);
  JacobianEvaluation J;
  evaluate_jacobian(T, J);
  std::vector<double> row_sum(size(), 0.0);  // sum_j |J_ij| C_i, W/K
  for (std::size_t i = 0; i < size(); ++i) row_sum[i] = std::abs(J.diagonal_W_per_K[i]);
  for (std::size_t e = 0; e < network_.edge_count(); ++e) {
    row_sum[network_.edge_a[e]] += std::abs(J.edge_W_per_K[e] + J.edge_ab_W_per_K[e]);
    row_sum[network_.edge_b[e]] += std::abs(J.edge_W_per_K[e] + J.edge_ba_W_per_K[e]);
  }
  double lambda_max = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (!network_.held[i])
      lambda_max = std::max(lambda_max, row_sum[i] / network_.heat_capacity_J_per_K[i]);
  return lambda_max > 0.0 ? 2.0 / lambda_max : std::numeric_limits<double>::infinity();
}

double ThermalSystem::thermal_energy_J(std::span<const double> T) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < size(); ++i) sum += network_.thermal_energy_at(i, T[i]);
  return sum;
}

}  // namespace tmdem::thermal
