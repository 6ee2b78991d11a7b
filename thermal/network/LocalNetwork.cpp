#include "thermal/network/LocalNetwork.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {
namespace {

// values[node[k]] for each local index k (empty stays empty: an optional per-node array).
template <class T>
std::vector<T> pick(const std::vector<T>& values, const std::vector<std::int32_t>& node) {
  std::vector<T> out;
  if (values.empty()) return out;
  out.reserve(node.size());
  for (const auto i : node) out.push_back(values[std::size_t(i)]);
  return out;
}

}  // namespace

LocalNetwork extract_local_network(const ThermalNetwork& g, const NetworkPartition& p, int rank) {
  if (p.node_count() != g.node_count())
    throw std::invalid_argument("extract_local_network: partition of " +
                                std::to_string(p.node_count()) + " nodes for a network of " +
                                std::to_string(g.node_count()));
  if (!g.dissipation_W.empty())
    throw std::invalid_argument(
        "heating over MPI takes a frozen packing; this network carries contact dissipation");
  LocalNetwork out;
  const std::int32_t first = p.first_row(rank), owned = p.owned_count(rank);
  out.owned = std::size_t(owned);
  for (std::int32_t k = 0; k < owned; ++k) {
    out.node.push_back(p.node_at_row(first + k));
    out.row.push_back(first + k);
  }
  // Ghosts: the other end of every edge that leaves this process, and per neighbour the owned
  // nodes it needs (the same edges seen from its side).
  std::vector<std::vector<std::int32_t>> ghost_rows(std::size_t(p.ranks())), send_rows(ghost_rows);
  for (std::size_t e = 0; e < g.edge_count(); ++e) {
    const int ra = p.owner(g.edge_a[e]), rb = p.owner(g.edge_b[e]);
    if ((ra == rank) == (rb == rank)) continue;  // inside this process, or not touching it
    const auto mine = ra == rank ? g.edge_a[e] : g.edge_b[e];
    const auto theirs = ra == rank ? g.edge_b[e] : g.edge_a[e];
    const int other = ra == rank ? rb : ra;
    ghost_rows[std::size_t(other)].push_back(p.row_of(theirs));
    send_rows[std::size_t(other)].push_back(p.row_of(mine));
  }
  std::vector<std::int32_t> local_of(g.node_count(), -1);
  for (std::int32_t k = 0; k < owned; ++k) local_of[std::size_t(out.node[std::size_t(k)])] = k;
  for (int r = 0; r < p.ranks(); ++r) {
    auto& ghosts = ghost_rows[std::size_t(r)];
    auto& sends = send_rows[std::size_t(r)];
    if (ghosts.empty()) continue;
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    std::sort(sends.begin(), sends.end());
    sends.erase(std::unique(sends.begin(), sends.end()), sends.end());
    GhostNeighbour n;
    n.rank = r;
    n.ghost_begin = std::int32_t(out.node.size());
    for (const auto row : ghosts) {
      const auto node = p.node_at_row(row);
      local_of[std::size_t(node)] = std::int32_t(out.node.size());
      out.node.push_back(node);
      out.row.push_back(row);
    }
    n.ghost_end = std::int32_t(out.node.size());
    for (const auto row : sends) n.send.push_back(row - first);
    out.neighbours.push_back(std::move(n));
  }

  ThermalNetwork& l = out.network;
  l.heat_capacity_J_per_K = pick(g.heat_capacity_J_per_K, out.node);
  l.surface_area_m2 = pick(g.surface_area_m2, out.node);
  l.radius_m = pick(g.radius_m, out.node);
  l.emissivity = pick(g.emissivity, out.node);
  l.heat_source_W = pick(g.heat_source_W, out.node);
  l.held = pick(g.held, out.node);
  l.node_material = pick(g.node_material, out.node);
  l.mass_kg = pick(g.mass_kg, out.node);
  l.shell_resistance_K_sr_per_W = pick(g.shell_resistance_K_sr_per_W, out.node);
  l.gas_shells_per_ray = g.gas_shells_per_ray;
  l.isothermal_walls = g.isothermal_walls;
  l.wall_temperature_tables = g.wall_temperature_tables;
  l.material_conductivity = g.material_conductivity;
  l.material_specific_heat = g.material_specific_heat;
  l.conductance_follows_conductivity = g.conductance_follows_conductivity;

  auto owns = [&](std::int32_t node) { return p.owner(node) == rank; };
  for (std::size_t e = 0; e < g.edge_count(); ++e) {
    if (!owns(g.edge_a[e]) && !owns(g.edge_b[e])) continue;
    l.add_edge(local_of[std::size_t(g.edge_a[e])], local_of[std::size_t(g.edge_b[e])],
               g.edge_conductance_W_per_K[e], g.edge_gap_m[e], g.edge_contact_radius_m[e],
               g.edge_in_contact[e] != 0);
  }
  for (std::size_t w = 0; w < g.wall_edge_count(); ++w) {
    if (!owns(g.wall_node[w])) continue;
    l.add_wall_edge(local_of[std::size_t(g.wall_node[w])], g.wall_temperature_K[w],
                    g.wall_conductance_W_per_K[w], g.wall_schedule[w], g.wall_gap_m[w],
                    g.wall_contact_radius_m[w], g.wall_in_contact[w] != 0);
    if (!g.wall_material.empty()) l.wall_material.push_back(g.wall_material[w]);
    if (!g.wall_emissivity.empty()) l.wall_emissivity.push_back(g.wall_emissivity[w]);
  }
  // Flux walls (WallFluxMode: q_i = P_w H_iw / sum_k H_kw): local power P_w times this
  // process's share of sum_k H_kw, so that the local sum divides it back to the global split.
  std::vector<double> total_W_per_K(g.flux_wall_power_W.size(), 0.0), mine_W_per_K(total_W_per_K);
  for (std::size_t f = 0; f < g.flux_edge_count(); ++f) {
    total_W_per_K[std::size_t(g.flux_wall[f])] += g.flux_conductance_W_per_K[f];
    if (!owns(g.flux_node[f])) continue;
    mine_W_per_K[std::size_t(g.flux_wall[f])] += g.flux_conductance_W_per_K[f];
    l.add_flux_edge(local_of[std::size_t(g.flux_node[f])], g.flux_wall[f],
                    g.flux_conductance_W_per_K[f]);
  }
  l.flux_wall_power_W = g.flux_wall_power_W;
  for (std::size_t w = 0; w < total_W_per_K.size(); ++w)
    if (total_W_per_K[w] > 0.0) l.flux_wall_power_W[w] *= mine_W_per_K[w] / total_W_per_K[w];
  return out;
}

}  // namespace tmdem::thermal
