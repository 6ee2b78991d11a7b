#pragma once
// Heating over MPI (`mpirun -np N tmdem run SCENE`, docs/scale-out.md): each process integrates
// only its own slab of particles (thermal::NetworkPartition::slabs across the bed's longest
// extent) on its thermal::LocalNetwork with ghost temperatures, by
// thermal::DistributedCvodeIntegrator (CG, BoomerAMG across the processes). The integrator
// gathers every temperature to every process after each advance, so the coupled run writes
// frames and the summary from rank 0 as in one process. The local network comes from the whole
// network every process built (HeatingSetUp::WholeNetwork: a settled bed, or frames with
// contacts), or from the process's own particles and those within reach of its slab alone
// (HeatingSetUp::Piece, BedPiece.h: mechanics off).
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/scene/Scene.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/network/LocalNetwork.h"
#include "thermal/network/NetworkPartition.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

// Why this scene cannot be heated over `processes` processes, or empty when it can: frozen beds
// only (mechanics "off", or "settle": every process settles the same packing), integrator
// "cvode" with linear_solver "amg" (or "auto", which is amg there), no gas layer shared by
// neighbour count, at least one particle per process. (A symmetric Jacobian is checked by the
// integrator, which sees the modes.) Checkpoints and restarts work as in one process: rank 0
// writes them, every process reads them.
std::string distributed_heating_refusal(const Scene& scene, int processes);

// Whether a process builds the whole bed's network or only its piece: the piece when the bed
// does not move (mechanics off) and no frame writes the contacts (rank 0 would need all of them).
enum class HeatingSetUp { WholeNetwork, Piece };
HeatingSetUp distributed_set_up(const Scene& scene);

class DistributedHeating {
 public:
  // Splits the bed over MPI_COMM_WORLD by the particle centres (3 per particle) and builds this
  // process's local system with the modes of `global` (the run's whole system). WholeNetwork:
  // the local network is extracted from global's network. Piece: global's network may hold the
  // nodes alone; the local network comes from BedPiece (collective: the flux walls'
  // conductances are summed over the processes).
  DistributedHeating(const Scene& scene, const thermal::ThermalSystem& global,
                     std::span<const double> position_m,
                     HeatingSetUp set_up = HeatingSetUp::WholeNetwork);
  // Refers to the local system: keep this object alive as long as the integrator.
  std::unique_ptr<thermal::ThermalIntegrator> make_integrator(
      const thermal::IntegratorSettings& settings);
  // The piece's layout (owned count, nodes, rows, neighbours); its network is in the local
  // system, which the integrator holds.
  const thermal::LocalNetwork& local() const { return local_; }
  // HeatingSetUp::Piece: the whole bed's start-up diagnostics, combined over the processes
  // (PieceDiagnostics.h); the other set-up leaves them to the whole network.
  const std::optional<ThermalDiagnostics>& diagnostics() const { return diagnostics_; }

 private:
  thermal::NetworkPartition partition_;
  thermal::LocalNetwork local_;
  std::unique_ptr<thermal::ThermalSystem> system_;
  std::optional<ThermalDiagnostics> diagnostics_;
};

}  // namespace tmdem::coupling
