#pragma once
// The coupled run's state and steps (CoupledRun.h describes the run), shared by the files that
// implement it: CoupledRun.cpp (the run as a whole: exit codes, status, the files closed),
// CoupledRunSetup.cpp (mechanics and thermal set-up), CoupledRunLoops.cpp (the time loops;
// "coupled" runs: CoupledRunThermoMechanics.cpp),
// CoupledRunResultFile.cpp (the result file and its frames), CoupledRunSummary.cpp (the
// summary) and CoupledRunCheckpoints.cpp (checkpoints, restarts and interruptions). Internal
// to the run room.
#include <chrono>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <stdexcept>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/bridge/CouplingStrategy.h"
#include "coupling/bridge/DynamicNetwork.h"
#include "coupling/output/Checkpoint.h"
#include "coupling/run/MechanicsStepLog.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/output/ResultWriter.h"
#include "coupling/output/RunSummary.h"
#include "coupling/run/CoupledRun.h"
#include "coupling/run/DistributedHeating.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/SettleProgress.h"
#include "coupling/run/ThermalExpansion.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling::run_detail {

// Settings found invalid once the run is set up (nothing written yet): exit 2.
struct StartError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A first SIGINT/SIGTERM was handled: last frame and checkpoint are written.
// Seconds since `start`: the measurement points of the loop add these up per part.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Interrupted {
  int signal = 0;
  double time_s = 0.0;    // simulated time reached, or settle time when settling
  bool settling = false;  // stopped while settling: a settle checkpoint was written (t = 0)
};

class CoupledRun {
 public:
  CoupledRun(const Scene& scene, const RunOptions& options, std::ostream& log)
      : scene_(scene), options_(options), log_(log),
        progress_(log, options.quiet, options.terminal),
        coupling_(parse_coupling_strategy(scene.thermal.coupling)) {}

  RunOutcome run();

 private:
  void restore_checkpoint();
  void prepare_mechanics();
  void settle();
  void prepare_thermal();
  // Over MPI: this process's share of the heating (DistributedHeating.h) as the integrator.
  void prepare_distributed_thermal(const thermal::IntegratorSettings& settings);
  void run_static();
  void run_dynamic();
  // effects.mechanics = "coupled" (CoupledRunThermoMechanics.cpp): heating between couplings,
  // each a quasi-static re-solve of the packing with the radii of the temperatures reached.
  void run_coupled();
  void recouple();
  void track_wall_forces();
  // The result file: created, or reopened to resume (rank 0 only over MPI).
  void open_result_file();
  void write_frame(double t_s);
  void maybe_checkpoint(double t_s);
  void checkpoint(double t_s);
  // A settle checkpoint (Checkpoint.h), written when a settle is interrupted and every
  // output.settle_checkpoint_interval of wall time while it lasts: the integrator's state and
  // where the settle stands, so that a restart resumes settling.
  void checkpoint_settle(const SettleProgress& where);
  void begin_thermal_segment(const CheckpointState& cs);
  void stop_if_interrupted(double t_s, bool frame_written);
  void fill_summary();
  std::span<const double> positions() const;
  std::span<const double> velocities() const;
  double max_temperature_K() const;
  std::vector<double> frame_times() const;

  Scene scene_;  // a copy: its pistons' points follow the mechanics (move_scene_walls)
  RunOptions options_;
  // Rank 0 writes the result, checkpoint and summary files; the other processes of a run over
  // MPI compute the same frames and checkpoints but write nothing.
  bool writes_files_ = thermal::MpiWorld::rank() == 0;
  // The run failed by an unexpected exception, which (over MPI) this process may have met alone.
  bool local_failure_ = false;
  std::ostream& log_;
  ProgressReporter progress_;
  CouplingStrategy coupling_;  // thermal.coupling, parsed once
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();

  mechanics::ParticleSet particles_;                  // used when mechanics is off or settled
  // Over MPI with each process building only its piece of the bed (HeatingSetUp::Piece): the
  // centres, 3 per particle, in place of particles_ and contacts_, which stay empty.
  std::vector<double> centre_m_;
  std::unique_ptr<mechanics::NscdIntegrator> nscd_;   // settle and dynamic
  // --step-log: a CSV line per mechanics step (rank 0), opened with the other outputs' checks.
  std::optional<MechanicsStepLog> step_log_;
  bool frozen_ = true;                                // positions no longer change
  std::vector<double> zero_velocity_;
  ContactList contacts_;
  std::vector<double> heat_flow_W_;                  // per contact, for the frames
  std::vector<double> series_conductance_W_per_K_;   // per contact, f H: particle resistance
  std::vector<double> wall_point_m_;                 // W*3, the walls' points, for the frames
  std::unique_ptr<DynamicNetwork> dynamic_network_;  // dynamic and coupled runs only
  std::optional<ThermalExpansion> expansion_;        // coupled runs only
  std::vector<double> radius_m_;                     // coupled: the radii of the last coupling
  ThermoMechanicsSummary thermo_;                    // coupled: couplings and wall forces
  std::unique_ptr<thermal::ThermalSystem> system_;
  std::optional<LinearSolverChoice> linear_solver_;  // thermal.linear_solver resolved on system_
  std::unique_ptr<DistributedHeating> distributed_;  // over MPI only; the integrator refers to it
  std::unique_ptr<thermal::ThermalIntegrator> integrator_;
  std::optional<ResultWriter> writer_;

  std::optional<CheckpointState> restart_;
  // A restart from a settle checkpoint: the run starts afresh (no result file yet, t = 0), its
  // settle resumed from this state instead of the scene's packing.
  std::optional<CheckpointState> settle_resume_;
  SettleProgress settle_progress_;  // where the run's settle stands (SettleProgress.h)
  // RESULT.checkpoint.h5 is a settle checkpoint this run wrote or resumed from (no later
  // checkpoint replaced it): removed when the run completes, as a restart from it would only
  // run the scene again.
  bool settle_checkpoint_on_disk_ = false;
  double t0_ = 0.0;
  std::vector<double> T0_;
  double boundary_heat0_J_ = 0.0;
  double initial_energy_J_ = 0.0;
  double contact_heat_J_ = 0.0;          // contacts' dissipation handed to the thermal side
  double dissipation_share_J_ = 0.0;     // exact integral of the free particles' share of it
  double dissipation_received0_J_ = 0.0; // what earlier thermal segments integrated of that share
  bool dissipation_heats_ = false;       // a switched-on mode turns it into heat
  double next_checkpoint_s_ = 0.0;
  double last_checkpoint_s_ = -1.0;     // time of the last checkpoint written, -1: none
  double thermal_seconds_ = 0.0;        // wall time inside the thermal side
  double mechanics_seconds_ = 0.0;      // wall time inside NSCD steps (settle and dynamic)
  double output_seconds_ = 0.0;         // wall time writing frames and checkpoints
  RunSummary summary_;
};

}  // namespace tmdem::coupling::run_detail
