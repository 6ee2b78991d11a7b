#pragma once
// One process's piece of a thermal network split by a NetworkPartition: its own nodes, then
// ghost copies of the other processes' nodes that share an edge with one of its own, and every
// edge that touches one of its own nodes. A ThermalSystem on this network gives the exact heat
// flow and Jacobian rows of the owned nodes once the ghosts hold their owners' temperatures
// (the ghosts' own rows are incomplete and never used). No MPI here: which values travel where
// is computed by every process from the same global network, so sender and receiver agree on
// the order without asking each other.
#include <cstdint>
#include <span>
#include <vector>

#include "thermal/network/NetworkPartition.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

// What this process exchanges with one other process at each ghost update.
struct GhostNeighbour {
  int rank = 0;
  std::vector<std::int32_t> send;  // local indices of owned nodes the neighbour holds as ghosts
  std::int32_t ghost_begin = 0;    // this process's ghosts of that neighbour: local indices
  std::int32_t ghost_end = 0;      //   [ghost_begin, ghost_end), in the same (row) order
};

struct LocalNetwork {
  // Nodes: the owned ones in row order (local index k = row - first_row), then the ghosts,
  // grouped by owner rank, each group in row order. Edges in the global network's order.
  ThermalNetwork network;
  std::size_t owned = 0;
  std::vector<std::int32_t> node;  // local index -> node id of the global network
  std::vector<std::int32_t> row;   // local index -> global row (NetworkPartition)
  std::vector<GhostNeighbour> neighbours;  // by rank
};

// Throws std::invalid_argument for a network with contact dissipation (a moving packing). A mode
// that looks at a node's whole neighbourhood (the gas layer shared by neighbour count) sees only
// part of a ghost's: the caller must not split such a system (coupling refuses it).
// Flux walls: each process's local power is the wall's power times its own contacts' share of
// the wall's conductance, so the wall's power is split across processes exactly as one
// process splits it.
LocalNetwork extract_local_network(const ThermalNetwork& global, const NetworkPartition& partition,
                                   int rank);

// The same from a piece of the network rather than the whole: `piece` holds some of the nodes
// (node_id: piece index -> node id of the whole network, the partition's numbering), among them
// every node `rank` owns, and every edge that touches one of those (others are ignored). The
// process built it from its own particles and those within reach (a frozen bed's local set-up),
// so it cannot sum a flux wall's conductance over the whole bed: flux_total_W_per_K gives those
// sums (one per flux wall: owned_flux_conductance_W_per_K added over the processes). Gives what
// the first form gives for the whole network, edges in the piece's order.
LocalNetwork extract_local_network(const ThermalNetwork& piece,
                                   std::span<const std::int32_t> node_id,
                                   const NetworkPartition& partition, int rank,
                                   std::span<const double> flux_total_W_per_K);

// Per flux wall, the summed conductance of the flux edges of the nodes `rank` owns, W/K.
std::vector<double> owned_flux_conductance_W_per_K(const ThermalNetwork& piece,
                                                   std::span<const std::int32_t> node_id,
                                                   const NetworkPartition& partition, int rank);

}  // namespace tmdem::thermal
