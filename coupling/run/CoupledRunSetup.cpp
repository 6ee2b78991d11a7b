// CoupledRun's set-up (CoupledRun.h describes the run): the mechanics (the particles, NSCD,
// settling until at rest, or the checkpointed state) and the thermal side (the network, the
// linear solver resolved from "auto", the integrator, over MPI this process's share).
#include <algorithm>
#include <memory>
#include <sstream>

#include "coupling/bridge/DynamicNetwork.h"
#include "coupling/bridge/RestingContacts.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/output/OutputError.h"
#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/RestartState.h"
#include "coupling/run/ThermalProblem.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/integrators/MpiWorld.h"

namespace tmdem::coupling::run_detail {

void CoupledRun::prepare_mechanics() {
  zero_velocity_.assign(3 * scene_.particles.size(), 0.0);
  if (thermal::MpiWorld::distributed() && distributed_set_up(scene_) == HeatingSetUp::Piece) {
    // Each process detects contacts in its piece of the bed alone (prepare_distributed_thermal):
    // the centres are all it keeps of the whole bed.
    if (restart_) {
      centre_m_ = restart_->position_m;
    } else {
      for (const auto& p : scene_.particles)
        centre_m_.insert(centre_m_.end(), p.position_m.begin(), p.position_m.end());
    }
    return;
  }
  particles_ = make_particle_set(scene_);
  if (restart_) {
    for (std::size_t i = 0; i < particles_.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        particles_.position[i][k] = restart_->position_m[3 * i + k];
        particles_.velocity[i][k] = restart_->velocity_m_per_s[3 * i + k];
        particles_.angular_velocity[i][k] = restart_->angular_velocity_rad_per_s[3 * i + k];
      }
  }
  const auto mode = scene_.effects.mechanics;
  if (mode == MechanicsMode::Off) {  // no mechanics: tangential force 0
    contacts_ = resting_contacts(scene_, particles_);
    return;
  }
  nscd_ = make_nscd_integrator(scene_, particles_);
  if (step_log_) step_log_->attach(*nscd_);
  if (settle_resume_) {
    // A settle resumed where its checkpoint stopped it: the integrator's whole state and the
    // settle's own (its rest test's window and counters), then settle() as in any run.
    try {
      nscd_->restore_state(mechanics_state_of(*settle_resume_));
      settle_progress_ = settle_progress_of(*settle_resume_);
    } catch (const std::invalid_argument& e) {
      throw StartError("settle checkpoint " + options_.restart_path + ": " + e.what());
    }
    move_scene_walls(scene_, nscd_->walls());
  }
  if (restart_) {
    // A settled run restarts on the frozen graph it checkpointed; a dynamic one from the
    // mechanics' whole state (candidate table and warm-start forces) when the checkpoint has it.
    contacts_ = contacts_of(*restart_, scene_.mechanics.time_step_s);
    nscd_->restore_stats(mechanics_stats_of(*restart_));
    if (mode == MechanicsMode::Coupled) {
      // The radii of the checkpoint's last coupling, before the state whose gaps they make.
      if (!restart_->has_mechanics || restart_->radius_m.size() != particles_.size())
        throw StartError("checkpoint " + options_.restart_path +
                         " holds no coupled run's mechanics (radii and candidate table)");
      std::copy(restart_->radius_m.begin(), restart_->radius_m.end(), nscd_->particles().radius.begin());
    }
    if ((mode == MechanicsMode::Dynamic || mode == MechanicsMode::Coupled) && restart_->has_mechanics) {
      try {
        nscd_->restore_state(mechanics_state_of(*restart_));
        move_scene_walls(scene_, nscd_->walls());
      } catch (const std::invalid_argument& e) {
        throw StartError("checkpoint " + options_.restart_path + ": " + e.what());
      }
    }
  }
  if (mode == MechanicsMode::Dynamic) {
    frozen_ = false;
    return;
  }
  if (mode == MechanicsMode::Coupled) {
    if (!restart_) settle();  // a restart goes on from the checkpoint's packing (above)
    frozen_ = false;  // the packing moves again at every coupling
    expansion_.emplace(scene_);
    return;
  }
  if (restart_) {
    particles_ = nscd_->particles();
    // The walls where settling left them, not where the scene put them: a piston's gas gaps
    // and its contacts' geometry are those of the checkpointed run (older checkpoints: scene's).
    const auto& points = restart_->settled_wall_point_m;
    if (points.size() == 3 * scene_.walls.size())
      for (std::size_t w = 0; w < scene_.walls.size(); ++w)
        for (int k = 0; k < 3; ++k) scene_.walls[w].point_m[k] = points[3 * w + k];
    return;
  }
  settle();
}

void CoupledRun::settle() {
  // A signal ends settling after the current step; the run then stops before t = 0 with a settle
  // checkpoint (no frame yet), from which a restart resumes settling. A settle that the same
  // step finished goes on into the run, which stops at t = 0 with a frame and a checkpoint.
  const auto mechanics_start = std::chrono::steady_clock::now();
  const double output_before_s = output_seconds_;  // settle checkpoints count as output
  // Settle checkpoints every output.settle_checkpoint_interval of wall time: a long settle
  // survives a crash (they do not change the settle: it reads nothing back from them).
  auto last_checkpoint = mechanics_start;
  const SettleCheckpoints checkpoints{
      [&] {
        const double interval_s = scene_.output.settle_checkpoint_interval_s;
        return interval_s > 0.0 && seconds_since(last_checkpoint) >= interval_s;
      },
      [&](const SettleProgress& where) {
        checkpoint_settle(where);
        last_checkpoint = std::chrono::steady_clock::now();
        if (writes_files_) {
          std::ostringstream said;
          said << "settle: checkpoint at t = " << where.time_s << " s of settle ("
               << where.steps << " steps) written to " << checkpoint_path_for(options_.output_path)
               << " (a crash resumes from it with --restart)";
          progress_.message(said.str());
        }
      }};
  // A mechanics error within the settle (a period too short for a particle kicked by a landing
  // piston) says when it came: it is not a scene refused at set-up.
  if (step_log_) step_log_->begin_phase("settle", settle_progress_.time_s);
  try {
    summary_.settle = settle_packing(*nscd_, scene_, progress_,
                                     &Interruption::requested, &settle_progress_,
                                     &checkpoints);
  } catch (const StartError&) {
    throw;
  } catch (const OutputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    const auto steps = nscd_->stats().steps;
    std::ostringstream message;
    message << "settling stopped at mechanics step " << steps + 1 << " (t = "
            << double(steps) * scene_.mechanics.time_step_s << " s of settle): " << e.what();
    throw std::runtime_error(message.str());
  }
  mechanics_seconds_ += seconds_since(mechanics_start) - (output_seconds_ - output_before_s);
  if (const int signal = Interruption::pending(); signal != 0 && !settle_progress_.finished) {
    checkpoint_settle(settle_progress_);
    throw Interrupted{signal, summary_.settle->time_s, true};
  }
  gather_contacts(nscd_->contacts(), contacts_);
  particles_ = nscd_->particles();
  move_scene_walls(scene_, nscd_->walls());
}

double CoupledRun::max_temperature_K() const {
  // The scene's only, also on restart: the explicit update adds the temperatures it starts
  // from itself, so a restart and the uninterrupted run's boundary see the same bound.
  return max_scene_temperature_K(scene_);
}

void CoupledRun::prepare_thermal() {
  // Each process's piece of the bed is built in prepare_distributed_thermal: here the whole
  // bed's nodes and modes alone (energy, heat capacities, the modes' names).
  if (centre_m_.empty())
    system_ = build_thermal_system(scene_, contacts_, frozen_ ? &particles_ : &nscd_->particles());
  else
    system_ = build_thermal_nodes(scene_);
  if (!frozen_) {
    dynamic_network_ = std::make_unique<DynamicNetwork>(scene_, *system_);
    // The network the checkpoint's step left, on the pattern it had: the same edges, in the
    // same order, as the uninterrupted run has at this time.
    if (restart_)
      dynamic_network_->restore(restart_->thermal_pattern_pair, contacts_, &nscd_->particles());
  }
  thermal::IntegratorSettings s;
  try {
    // "auto" resolved here, once: the integrator, the report and the summary name this solver.
    linear_solver_ = choose_linear_solver(scene_, *system_, thermal::MpiWorld::size());
    s = integrator_settings(scene_, linear_solver_->kind);
    s.max_temperature_K = max_temperature_K();
    if (thermal::MpiWorld::distributed())
      prepare_distributed_thermal(s);
    else
      integrator_ = thermal::make_thermal_integrator(scene_.thermal.integrator, *system_, s);
    if (T0_.empty())
      for (const auto& p : scene_.particles) T0_.push_back(p.temperature_K);
    if (restart_)
      begin_thermal_segment(*restart_);
    else
      integrator_->initialize(t0_, T0_, boundary_heat0_J_);
  } catch (const std::invalid_argument& e) {
    throw StartError(e.what());
  }
  if (!restart_) initial_energy_J_ = system_->thermal_energy_J(T0_);
  if (!options_.quiet) {
    std::ostringstream report;
    report << "thermal: integrator " << scene_.thermal.integrator;
    if (!integrator_->is_explicit())
      report << " (" << linear_solver_->name()
             << (linear_solver_->automatic ? "; " + linear_solver_->reason : "") << ")";
    report << ", modes:";
    for (const auto& m : system_->modes()) report << " " << m->name();
    report << "\n";
    // Each process holding only its piece: combined from the processes' own particles.
    print_diagnostics(report, distributed_ && distributed_->diagnostics()
                                  ? *distributed_->diagnostics()
                                  : diagnose(scene_, contacts_, *system_, s.max_temperature_K));
    progress_.message(report.str().substr(0, report.str().size() - 1));
  }
}

void CoupledRun::prepare_distributed_thermal(const thermal::IntegratorSettings& settings) {
  // Every process settled on its own: the packings must be the same bits, or the processes
  // would split different networks.
  if (scene_.effects.mechanics == MechanicsMode::Settle) {
    double fingerprint = 0.0;
    for (std::size_t k = 0; k < contacts_.normal_force_N.size(); ++k)
      fingerprint += double(k + 1) * (contacts_.normal_force_N[k] + double(contacts_.pair[2 * k]) +
                                      0.5 * double(contacts_.pair[2 * k + 1]));
    for (const double x : positions()) fingerprint += x;
    if (!thermal::MpiWorld::same_everywhere(fingerprint))
      throw StartError("heating over MPI: the processes settled different packings (the settling "
                       "is repeated in every process and must give the same bits; are their "
                       "OpenMP thread counts equal?)");
  }
  distributed_ = std::make_unique<DistributedHeating>(scene_, *system_, positions(),
                                                      distributed_set_up(scene_));
  integrator_ = distributed_->make_integrator(settings);
  const auto& local = distributed_->local();
  summary_.mpi = MpiSummary{thermal::MpiWorld::size(),
                            std::int64_t(thermal::MpiWorld::sum(double(local.node.size() - local.owned)))};
  if (!options_.quiet) {
    std::ostringstream report;
    report << "thermal: heating over " << thermal::MpiWorld::size()
           << " MPI processes, slabs across the bed; rank 0 integrates " << local.owned
           << " particles with " << local.node.size() - local.owned << " ghosts";
    progress_.message(report.str());
  }
}

}  // namespace tmdem::coupling::run_detail
