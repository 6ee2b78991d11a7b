#pragma once
// The start-up diagnostics (coupling/bridge/ThermalDiagnostics.h) of a bed heated over MPI
// with each process holding only its piece (BedPiece.h): each process takes the figures of the
// particles it owns, whose contacts its piece holds whole, and the processes combine them, so
// the run prints what one process prints.
#include <cstdint>
#include <span>

#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"
#include "thermal/network/NetworkPartition.h"

namespace tmdem::coupling {

// This process's share, no MPI: the heat-carrying contacts whose first particle it owns, the
// largest Biot number of its own particles' contact ends (the smallest id among equal ones),
// their time constants (min_time_constant_s +infinity when none has a conductance) and those
// without a conductance. explicit_bound_s is left to the caller: the local system's bound (its
// own rows are whole, its ghosts' partial, so the smallest over the processes is the bed's).
// contacts: the piece's, in piece indices, with their conductances; particle: piece index ->
// scene id; heat_capacity_J_per_K: per piece index.
ThermalDiagnostics diagnose_piece(const Scene& scene, const ContactList& contacts,
                                  std::span<const std::int32_t> particle,
                                  std::span<const double> heat_capacity_J_per_K,
                                  const thermal::NetworkPartition& partition, int rank);

// The whole bed's figures from every process's share: counts added, the largest Biot number
// (named by the smallest particle id among equal ones, where one process names the first in
// contact order: mostly the same, e.g. a uniform lattice's particle 0), the extreme time
// constants, the smallest explicit bound. No MPI.
ThermalDiagnostics combine_shares(std::span<const ThermalDiagnostics> shares);

// combine_shares over MPI_COMM_WORLD (collective): every process gets the whole bed's figures.
ThermalDiagnostics combine_over_processes(const ThermalDiagnostics& mine);

}  // namespace tmdem::coupling
