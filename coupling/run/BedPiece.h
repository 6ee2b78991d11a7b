#pragma once
// One process's share of a frozen bed's set-up when the heating runs over MPI with mechanics
// off (docs/scale-out.md): rather than detecting the whole bed's contacts and building its whole
// network in every process, each keeps the particles it owns (its slab of the partition) and
// those within a detection halo of the slab, detects contacts among those alone and builds the
// network from them. An owned particle's contacts and near pairs (and the particles that may
// shadow them) all lie within the halo, so its edges are the whole bed's: extract_local_network
// on this piece gives the local network the whole network gives (tested).
#include <cstdint>
#include <span>
#include <vector>

#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/scene/Scene.h"
#include "thermal/network/NetworkPartition.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::coupling {

struct BedPiece {
  // Piece index -> scene particle id, increasing: the contacts' canonical (i, j) order among the
  // piece's particles is the scene's.
  std::vector<std::int32_t> particle;
  std::size_t contacts = 0;  // detected among the piece's particles and with the walls
  // This process's share of the start-up diagnostics (PieceDiagnostics.h), taken from the
  // contacts before they are dropped: the network is all that is kept of them.
  ThermalDiagnostics diagnostics;
  // Nodes: the piece's particles, by piece index; edges from their contacts (and near pairs for
  // the gap modes). Edges between two halo particles are there too; extraction drops them.
  thermal::ThermalNetwork network;

  // centre_m: every particle's centre (3 per particle, the frozen packing), the partition's
  // input; the particles' other data come from the scene.
  static BedPiece build(const Scene& scene, std::span<const double> centre_m,
                        const thermal::NetworkPartition& partition, int rank);
};

// How far beyond its slab a process keeps particles, m: (3 + near reach) r_max. A particle's
// contacts and near pairs have their centres within (2 + near reach) r_max of its own, and a
// particle that shadows a near pair has its centre within its radius of the pair's centre line.
double detection_halo_m(const Scene& scene);

}  // namespace tmdem::coupling
