#include "coupling/run/DistributedHeating.h"

#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/run/BedPiece.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/PieceDiagnostics.h"
#include "coupling/run/ThermalProblem.h"
#include "thermal/integrators/DistributedCvodeIntegrator.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {
namespace {

bool gas_layer_shared(const Scene& scene) {
  const auto* gas = thermal::find_heat_transfer_mode("gas_conduction");
  if (!gas) return false;
  ThermalNetworkBuilder builder(scene);
  return thermal::resolve_mode_parameters(*gas, builder.mode_settings()).choice("layer_share") ==
         "equal_solid_angle";
}

}  // namespace

std::string distributed_heating_refusal(const Scene& scene, int processes) {
  const std::string over = "heating over MPI (" + std::to_string(processes) + " processes): ";
  if (scene.effects.mechanics == MechanicsMode::Dynamic || scene.effects.mechanics == MechanicsMode::Coupled)
    return over + "effects.mechanics = \"" +
           (scene.effects.mechanics == MechanicsMode::Dynamic ? "dynamic" : "coupled") +
           "\" changes the contact graph during the run; only frozen beds are split (\"off\", "
           "or \"settle\"), or run with one process";
  if (thermal::parse_integrator_kind(scene.thermal.integrator) != thermal::IntegratorKind::Cvode)
    return over + "thermal.integrator = \"" + scene.thermal.integrator +
           "\" runs in one process only; use \"cvode\"";
  // "auto" is amg over several processes; an explicit klu or pcg is refused.
  if (const auto choice = choose_distributed_linear_solver(scene, processes);
      !choice.refusal.empty())
    return over + choice.refusal;
  if (scene.particles.size() < std::size_t(processes))
    return over + "fewer particles (" + std::to_string(scene.particles.size()) + ") than processes";
  if (gas_layer_shared(scene))
    return over + "gas.layer_share = \"equal_solid_angle\" needs each particle's whole "
                  "neighbourhood, which a process does not hold for another's particles";
  return "";
}

HeatingSetUp distributed_set_up(const Scene& scene) {
  return scene.effects.mechanics == MechanicsMode::Off && !scene.output.contacts
             ? HeatingSetUp::Piece
             : HeatingSetUp::WholeNetwork;
}

DistributedHeating::DistributedHeating(const Scene& scene, const thermal::ThermalSystem& global,
                                       std::span<const double> position_m, HeatingSetUp set_up)
    : partition_(thermal::NetworkPartition::slabs(position_m, thermal::MpiWorld::size())) {
  const int rank = thermal::MpiWorld::rank();
  if (set_up == HeatingSetUp::Piece) {
    // This process's piece of the bed alone (BedPiece.h); freed once its network is extracted.
    const auto piece = BedPiece::build(scene, position_m, partition_, rank);
    auto total_W_per_K =
        thermal::owned_flux_conductance_W_per_K(piece.network, piece.particle, partition_, rank);
    for (auto& conductance : total_W_per_K) conductance = thermal::MpiWorld::sum(conductance);
    local_ = thermal::extract_local_network(piece.network, piece.particle, partition_, rank,
                                            total_W_per_K);
    diagnostics_ = piece.diagnostics;
  } else {
    local_ = thermal::extract_local_network(global.network(), partition_, rank);
  }
  // The same modes as the global system, built afresh for the local network (a mode prepares
  // per-edge data for the network it is given).
  ThermalNetworkBuilder builder(scene);
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> modes;
  for (const auto& mode : global.modes())
    modes.push_back(thermal::make_heat_transfer_mode(std::string(mode->name()),
                                                     builder.mode_settings()));
  // The piece's network moves into its system (one copy, not two; local_.network is left empty).
  system_ = std::make_unique<thermal::ThermalSystem>(std::move(local_.network), std::move(modes));
  if (diagnostics_) {
    diagnostics_->explicit_bound_s =
        system_->explicit_stability_bound_s(max_scene_temperature_K(scene));
    diagnostics_ = combine_over_processes(*diagnostics_);
  }
}

std::unique_ptr<thermal::ThermalIntegrator> DistributedHeating::make_integrator(
    const thermal::IntegratorSettings& settings) {
  return std::make_unique<thermal::DistributedCvodeIntegrator>(*system_, local_, partition_,
                                                               settings);
}

}  // namespace tmdem::coupling
