#include "thermal/network/LocalNetwork.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {
namespace {

// values[piece[k]] for each local index k (empty stays empty: an optional per-node array).
template <class T>
std::vector<T> pick(const std::vector<T>& values, const std::vector<std::int32_t>& piece) {
  std::vector<T> out;
  if (values.empty()) return out;
  out.reserve(piece.size());
  for (const auto i : piece) out.push_back(values[std::size_t(i)]);
  return out;
}

}  // namespace

std::vector<double> owned_flux_conductance_W_per_K(const ThermalNetwork& piece,
                                                   std::span<const std::int32_t> node_id,
                                                   const NetworkPartition& p, int rank) {
  std::vector<double> mine_W_per_K(piece.flux_wall_power_W.size(), 0.0);
  for (std::size_t f = 0; f < piece.flux_edge_count(); ++f)
    if (p.owner(node_id[std::size_t(piece.flux_node[f])]) == rank)
      mine_W_per_K[std::size_t(piece.flux_wall[f])] += piece.flux_conductance_W_per_K[f];
  return mine_W_per_K;
}

LocalNetwork extract_local_network(const ThermalNetwork& g, const NetworkPartition& p, int rank) {
  if (p.node_count() != g.node_count())
    throw std::invalid_argument("extract_local_network: partition of " +
                                std::to_string(p.node_count()) + " nodes for a network of " +
                                std::to_string(g.node_count()));
  std::vector<std::int32_t> identity(g.node_count());
  std::iota(identity.begin(), identity.end(), 0);
  std::vector<double> total_W_per_K(g.flux_wall_power_W.size(), 0.0);
  for (std::size_t f = 0; f < g.flux_edge_count(); ++f)
    total_W_per_K[std::size_t(g.flux_wall[f])] += g.flux_conductance_W_per_K[f];
  return extract_local_network(g, identity, p, rank, total_W_per_K);
}

LocalNetwork extract_local_network(const ThermalNetwork& g, std::span<const std::int32_t> node_id,
                                   const NetworkPartition& p, int rank,
                                   std::span<const double> flux_total_W_per_K) {
  if (node_id.size() != g.node_count())
    throw std::invalid_argument("extract_local_network: " + std::to_string(node_id.size()) +
                                " node ids for a network of " + std::to_string(g.node_count()));
  if (flux_total_W_per_K.size() != g.flux_wall_power_W.size())
    throw std::invalid_argument("extract_local_network: conductance totals for " +
                                std::to_string(flux_total_W_per_K.size()) + " flux walls, not " +
                                std::to_string(g.flux_wall_power_W.size()));
  if (!g.dissipation_W.empty())
    throw std::invalid_argument(
        "heating over MPI takes a frozen packing; this network carries contact dissipation");
  const auto owner = [&](std::int32_t k) { return p.owner(node_id[std::size_t(k)]); };
  const auto row = [&](std::int32_t k) { return p.row_of(node_id[std::size_t(k)]); };
  LocalNetwork out;
  const std::int32_t first = p.first_row(rank), owned = p.owned_count(rank);
  out.owned = std::size_t(owned);
  // Piece index of each local index: the owned nodes in row order, then the ghosts.
  std::vector<std::int32_t> piece;
  piece.reserve(std::size_t(owned));
  for (std::int32_t k = 0; k < std::int32_t(g.node_count()); ++k)
    if (owner(k) == rank) piece.push_back(k);
  if (piece.size() != std::size_t(owned))
    throw std::invalid_argument("extract_local_network: the network holds " +
                                std::to_string(piece.size()) + " of the " +
                                std::to_string(owned) + " nodes of process " +
                                std::to_string(rank));
  std::sort(piece.begin(), piece.end(), [&](auto a, auto b) { return row(a) < row(b); });
  for (const auto k : piece) out.row.push_back(row(k));
  // Ghosts: the other end of every edge that leaves this process, and per neighbour the owned
  // nodes it needs (the same edges seen from its side). Held as (row, piece index).
  using Entry = std::pair<std::int32_t, std::int32_t>;
  std::vector<std::vector<Entry>> ghosts(std::size_t(p.ranks())), sends(ghosts);
  for (std::size_t e = 0; e < g.edge_count(); ++e) {
    const int ra = owner(g.edge_a[e]), rb = owner(g.edge_b[e]);
    if ((ra == rank) == (rb == rank)) continue;  // inside this process, or not touching it
    const auto mine = ra == rank ? g.edge_a[e] : g.edge_b[e];
    const auto theirs = ra == rank ? g.edge_b[e] : g.edge_a[e];
    const int other = ra == rank ? rb : ra;
    ghosts[std::size_t(other)].emplace_back(row(theirs), theirs);
    sends[std::size_t(other)].emplace_back(row(mine), mine);
  }
  std::vector<std::int32_t> local_of(g.node_count(), -1);
  for (std::int32_t k = 0; k < owned; ++k) local_of[std::size_t(piece[std::size_t(k)])] = k;
  for (int r = 0; r < p.ranks(); ++r) {
    auto& from = ghosts[std::size_t(r)];
    auto& to = sends[std::size_t(r)];
    if (from.empty()) continue;
    std::sort(from.begin(), from.end());
    from.erase(std::unique(from.begin(), from.end()), from.end());
    std::sort(to.begin(), to.end());
    to.erase(std::unique(to.begin(), to.end()), to.end());
    GhostNeighbour n;
    n.rank = r;
    n.ghost_begin = std::int32_t(piece.size());
    for (const auto& [ghost_row, k] : from) {
      local_of[std::size_t(k)] = std::int32_t(piece.size());
      piece.push_back(k);
      out.row.push_back(ghost_row);
    }
    n.ghost_end = std::int32_t(piece.size());
    for (const auto& [send_row, k] : to) n.send.push_back(send_row - first);
    out.neighbours.push_back(std::move(n));
  }
  for (const auto k : piece) out.node.push_back(node_id[std::size_t(k)]);

  ThermalNetwork& l = out.network;
  l.heat_capacity_J_per_K = pick(g.heat_capacity_J_per_K, piece);
  l.surface_area_m2 = pick(g.surface_area_m2, piece);
  l.radius_m = pick(g.radius_m, piece);
  l.emissivity = pick(g.emissivity, piece);
  l.heat_source_W = pick(g.heat_source_W, piece);
  l.held = pick(g.held, piece);
  l.node_material = pick(g.node_material, piece);
  l.mass_kg = pick(g.mass_kg, piece);
  l.shell_resistance_K_sr_per_W = pick(g.shell_resistance_K_sr_per_W, piece);
  l.gas_shells_per_ray = g.gas_shells_per_ray;
  l.isothermal_walls = g.isothermal_walls;
  l.wall_temperature_tables = g.wall_temperature_tables;
  l.material_conductivity = g.material_conductivity;
  l.material_specific_heat = g.material_specific_heat;
  l.conductance_follows_conductivity = g.conductance_follows_conductivity;

  auto owns = [&](std::int32_t k) { return owner(k) == rank; };
  for (std::size_t e = 0; e < g.edge_count(); ++e) {
    if (!owns(g.edge_a[e]) && !owns(g.edge_b[e])) continue;
    l.add_edge(local_of[std::size_t(g.edge_a[e])], local_of[std::size_t(g.edge_b[e])],
               g.edge_conductance_W_per_K[e], g.edge_gap_m[e], g.edge_contact_radius_m[e],
               g.edge_in_contact[e] != 0);
    if (!g.edge_shadowed.empty()) l.edge_shadowed.push_back(g.edge_shadowed[e]);
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
  for (std::size_t f = 0; f < g.flux_edge_count(); ++f) {
    if (!owns(g.flux_node[f])) continue;
    l.add_flux_edge(local_of[std::size_t(g.flux_node[f])], g.flux_wall[f],
                    g.flux_conductance_W_per_K[f]);
  }
  const auto mine_W_per_K = owned_flux_conductance_W_per_K(g, node_id, p, rank);
  l.flux_wall_power_W = g.flux_wall_power_W;
  for (std::size_t w = 0; w < flux_total_W_per_K.size(); ++w)
    if (flux_total_W_per_K[w] > 0.0)
      l.flux_wall_power_W[w] *= mine_W_per_K[w] / flux_total_W_per_K[w];
  return out;
}

}  // namespace tmdem::thermal
