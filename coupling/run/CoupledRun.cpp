#include "coupling/run/CoupledRun.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <omp.h>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "coupling/bridge/ContactHeatFlow.h"
#include "coupling/bridge/ContactList.h"
#include "coupling/bridge/ContactSeriesFactors.h"
#include "coupling/bridge/DynamicNetwork.h"
#include "coupling/bridge/RestingContacts.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/Checkpoint.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/output/ResultWriter.h"
#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/OutputPaths.h"
#include "coupling/run/RestartState.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/HeatModes.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/integrators/ThermalSolverError.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

std::string checkpoint_path_for(const std::string& output_path) {
  const std::string ext = ".h5";
  if (output_path.size() > ext.size() &&
      output_path.compare(output_path.size() - ext.size(), ext.size(), ext) == 0)
    return output_path.substr(0, output_path.size() - ext.size()) + ".checkpoint.h5";
  return output_path + ".checkpoint.h5";
}

namespace run_detail {

void CoupledRun::prepare_mechanics() {
  particles_ = make_particle_set(scene_);
  zero_velocity_.assign(3 * scene_.particles.size(), 0.0);
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
  // A signal ends settling after the current step; the run then stops before t = 0: there is
  // no frame to write and nothing to resume (a restart starts from a settled packing).
  const auto mechanics_start = std::chrono::steady_clock::now();
  summary_.settle = settle_packing(*nscd_, scene_, progress_, [] { return Interruption::pending() != 0; });
  mechanics_seconds_ += seconds_since(mechanics_start);
  if (const int signal = Interruption::pending(); signal != 0)
    throw Interrupted{signal, summary_.settle->time_s};
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
  system_ = build_thermal_system(scene_, contacts_, frozen_ ? &particles_ : &nscd_->particles());
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
    print_diagnostics(report, diagnose(scene_, contacts_, *system_, s.max_temperature_K));
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
  distributed_ = std::make_unique<DistributedHeating>(scene_, *system_, positions());
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

std::span<const double> CoupledRun::positions() const {
  const auto& p = nscd_ && !frozen_ ? nscd_->particles().position : particles_.position;
  return {p.empty() ? nullptr : p.front().data(), 3 * p.size()};
}

std::span<const double> CoupledRun::velocities() const {
  if (frozen_) return zero_velocity_;
  const auto& v = nscd_->particles().velocity;
  return {v.empty() ? nullptr : v.front().data(), 3 * v.size()};
}

void CoupledRun::write_frame(double t_s) {
  if (!writes_files_) return;  // over MPI rank 0 alone builds and writes the frames
  const auto output_start = std::chrono::steady_clock::now();
  FrameView f;
  f.time_s = t_s;
  f.position_m = positions();
  f.velocity_m_per_s = velocities();
  f.temperature_K = integrator_->temperatures_K();
  f.thermal_energy_J = system_->thermal_energy_J(f.temperature_K);
  f.boundary_heat_J = integrator_->boundary_heat_J();
  f.contact_pair = contacts_.pair;
  f.normal_force_N = contacts_.normal_force_N;
  f.tangential_force_N = contacts_.tangential_force_N;
  // With the particle's own resistance, each contact's conductance and flow are those of the
  // path in series with the two shells (ContactSeriesFactors.h).
  const bool in_series =
      contact_conductances_in_series(contacts_, system_->network(), series_conductance_W_per_K_);
  f.conductance_W_per_K = in_series ? series_conductance_W_per_K_ : contacts_.conductance_W_per_K;
  contact_heat_flow_W(contacts_, f.conductance_W_per_K, f.temperature_K, t_s, scene_, heat_flow_W_);
  f.heat_flow_W = heat_flow_W_;
  wall_point_m_.clear();  // where the walls are now: pistons move (move_scene_walls)
  for (const auto& wall : scene_.walls) wall_point_m_.insert(wall_point_m_.end(), wall.point_m.begin(), wall.point_m.end());
  f.wall_point_m = wall_point_m_;
  writer_->write_frame(f);
  output_seconds_ += seconds_since(output_start);
}

std::vector<double> CoupledRun::frame_times() const {
  std::vector<double> times;
  const double dt = scene_.output.interval_s, end = scene_.duration_s;
  for (long k = 0;; ++k) {
    const double t = double(k) * dt;
    if (t >= end - 1e-9 * dt) break;
    times.push_back(t);
  }
  times.push_back(end);
  return times;
}

void CoupledRun::run_static() {
  const auto times = frame_times();
  for (double t : times) {
    if (t < t0_ - 1e-12) continue;
    if (t > t0_ + 1e-12 || !restart_) {
      const auto thermal_start = std::chrono::steady_clock::now();
      integrator_->advance_to(t);
      thermal_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - thermal_start).count();
      write_frame(t);
    }
    maybe_checkpoint(t);
    stop_if_interrupted(t, true);
    const auto st = integrator_->stats();
    progress_.update("run", t, scene_.duration_s, std::to_string(st.steps) + " thermal steps");
  }
}

void CoupledRun::run_dynamic() {
  const double h = scene_.mechanics.time_step_s;
  dissipation_heats_ = contacts_dissipate_heat(scene_.effects);
  const auto times = frame_times();
  std::size_t next_frame = 0;
  while (next_frame < times.size() && times[next_frame] < t0_ + 0.5 * h) ++next_frame;
  if (!restart_) write_frame(0.0);
  double t = t0_;
  long k = std::lround(t0_ / h);
  while (t < scene_.duration_s - 1e-9 * h) {
    ++k;
    const double t_next = std::min(double(k) * h, scene_.duration_s);
    const auto mechanics_start = std::chrono::steady_clock::now();
    const auto report = nscd_->step(t_next - t);
    mechanics_seconds_ += seconds_since(mechanics_start);
    if (!report.converged && !options_.quiet && nscd_->stats().unconverged_steps <= 10) {
      std::string msg = unconverged_step_warning("mechanics step", t_next, *nscd_, report,
                                                 report.tolerance);
      if (nscd_->stats().unconverged_steps == 10) msg += "; further such warnings are not shown";
      progress_.message(msg);
    }
    gather_contacts(nscd_->contacts(), contacts_);
    move_scene_walls(scene_, nscd_->walls());  // near pairs see the pistons where they are
    const auto thermal_start = std::chrono::steady_clock::now();
    dynamic_network_->update(contacts_, *integrator_, coupling_, &nscd_->particles());
    integrator_->advance_to(t_next);
    if (dissipation_heats_) {  // the power the network carried over [t, t_next]
      double power_W = 0.0;
      for (const double P : contacts_.dissipated_power_W) power_W += P;
      contact_heat_J_ += power_W * (t_next - t);
      dissipation_share_J_ += system_->dissipation_boundary_W() * (t_next - t);
    }
    thermal_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - thermal_start).count();
    t = t_next;
    bool frame_written = false;
    if (next_frame < times.size() && t >= times[next_frame] - 0.5 * h) {
      write_frame(t);
      frame_written = true;
      while (next_frame < times.size() && times[next_frame] < t + 0.5 * h) ++next_frame;
    }
    maybe_checkpoint(t);
    stop_if_interrupted(t, frame_written);
    progress_.update("run", t, scene_.duration_s,
                     std::to_string(contacts_.size()) + " contacts");
  }
}

void CoupledRun::fill_summary() {
  summary_.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  summary_.particles = std::int64_t(scene_.particles.size());
  WallTimeParts parts;
  parts.mechanics_s = mechanics_seconds_;
  parts.thermal_s = thermal_seconds_;
  parts.output_s = output_seconds_;
  parts.other_s = std::max(0.0, summary_.wall_time_s - parts.mechanics_s - parts.thermal_s -
                                    parts.output_s);
  if (nscd_) {  // timed inside the steps, so within mechanics_s
    parts.detection_s = nscd_->stats().detection_s;
    parts.contact_solve_s = nscd_->stats().solve_s;
    parts.correction_s = nscd_->stats().correction_s;
  }
  summary_.wall_time_parts = parts;
  if (scene_.effects.mechanics == MechanicsMode::Coupled) summary_.thermo_mechanics = thermo_;
  const char* wait_policy = std::getenv("OMP_WAIT_POLICY");
  const char* spin_count = std::getenv("GOMP_SPINCOUNT");
  summary_.openmp = OpenMpSummary{omp_get_max_threads(), wait_policy ? wait_policy : "unset",
                                  spin_count ? spin_count : "unset"};
  summary_.imports.clear();
  for (const auto& i : scene_.imports)
    summary_.imports.push_back({i.file, std::int64_t(i.count), i.largest_overlap, i.overlap_tolerance});
  if (nscd_) {
    const auto& ms = nscd_->stats();
    summary_.mechanics.steps = ms.steps;
    summary_.mechanics.mean_iterations = ms.mean_sweeps();
    summary_.mechanics.max_iterations = ms.max_sweeps;
    summary_.mechanics.unconverged_steps = ms.unconverged_steps;
    summary_.mechanics.max_penetration_m = ms.max_penetration_m;
    summary_.mechanics.stalled_steps = ms.stalled_steps;
    summary_.mechanics.correction_sweeps = ms.correction_sweeps;
    summary_.mechanics.max_step_travel_m = ms.max_travel_m;
    summary_.mechanics.max_siconos_residual = ms.max_siconos_residual;
    summary_.mechanics.siconos_unconverged_steps = ms.siconos_unconverged_steps;
    if (nscd_->tolerance_schedule().enabled()) {
      ToleranceScheduleSummary ts;
      ts.tolerance = scene_.mechanics.tolerance;
      // In force: the fall speed may be automatic, the fall tolerance no tighter than tolerance.
      ts.fall_tolerance = nscd_->tolerance_schedule().fall_tolerance();
      ts.fall_speed_m_s = nscd_->tolerance_schedule().fall_speed_m_per_s();
      ts.fall_share = scene_.mechanics.fall_share;
      ts.fall_steps = ms.fall_steps;
      ts.fall_unconverged_steps = ms.fall_unconverged_steps;
      ts.tighten_steps = scene_.mechanics.tighten_steps;
      const std::int64_t landed = nscd_->tolerance_schedule().landed_step();
      ts.tightened = landed > 0;
      ts.tightened_step = landed;
      // Every step but a dynamic run's last is time_step long.
      ts.tightened_time_s = landed > 0 ? double(landed - 1) * scene_.mechanics.time_step_s : 0.0;
      summary_.mechanics.tolerance_schedule = ts;
    }
    // Settle runs too (their settle phase); heat is handed over by dynamic runs only.
    MechanicalEnergySummary m;
    m.energy_change_J = ms.energy_change_J;
    m.contact_dissipation_J = ms.contact_dissipation_J;
    m.numerical_dissipation_J = ms.numerical_dissipation_J;
    m.correction_potential_J = ms.correction_potential_J;
    m.heat_generated_J = contact_heat_J_;
    m.heat_share_J = dissipation_share_J_;
    m.heat_received_J =
        dissipation_received0_J_ + (integrator_ ? integrator_->dissipation_heat_J() : 0.0);
    summary_.energy.mechanical =
        m.with_errors(!frozen_ && contacts_dissipate_heat(scene_.effects));
  }
  summary_.thermal.integrator = scene_.thermal.integrator;
  const bool explicit_update =
      thermal::parse_integrator_kind(scene_.thermal.integrator) == thermal::IntegratorKind::Explicit;
  // The resolved solver; none when the run failed before its thermal side was set up.
  if (!explicit_update && linear_solver_) {
    summary_.thermal.linear_solver = linear_solver_->name();
    summary_.thermal.linear_solver_reason = linear_solver_->reason;
  }
  if (integrator_) {
    const auto st = integrator_->stats();
    summary_.thermal.steps = st.steps;
    summary_.thermal.rhs_evals = st.rhs_evals;
    summary_.thermal.jacobian_evals = st.jacobian_evals;
    summary_.thermal.linear_setups = st.linear_setups;
    summary_.thermal.error_test_failures = st.error_test_failures;
    summary_.thermal.convergence_failures = st.convergence_failures;
    summary_.thermal.reinitializations = st.reinitializations;
    summary_.thermal.wall_time_s = thermal_seconds_;
    if (!frozen_) summary_.thermal.coupling = scene_.thermal.coupling;
    summary_.simulated_time_s = integrator_->time_s();
    summary_.energy.initial_J = initial_energy_J_;
    summary_.energy.final_J = system_->thermal_energy_J(integrator_->temperatures_K());
    summary_.energy.boundary_heat_J = integrator_->boundary_heat_J();
    summary_.energy.balance_error_rel = RunSummary::balance_error_rel(
        summary_.energy.initial_J, summary_.energy.final_J, summary_.energy.boundary_heat_J);
  }
}

void CoupledRun::open_result_file() {
  if (restart_) {
    RestartMatch match;
    match.particles = scene_.particles.size();
    match.scene_toml = restart_->scene_toml;
    match.checkpoint_time_s = restart_->time_s;
    match.next_scene_toml = scene_.resolved_toml;
    match.contact_tail = &restart_->result_contact_tail;
    writer_.emplace(ResultWriter::reopen(options_.output_path,
                                         std::size_t(restart_->frames_written), &match));
  } else {
    ResultHeader header;
    header.scene_toml = scene_.resolved_toml;
    for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
      const auto& p = scene_.particles[i];
      header.radius_m.push_back(p.radius_m);
      header.mass_kg.push_back(particle_mass_kg(scene_, i));
      header.heat_capacity_J_per_K.push_back(system_->network().heat_capacity_J_per_K[i]);
      header.material.push_back(p.material);
    }
    for (const auto& m : scene_.materials) header.material_names.push_back(m.name);
    for (const auto& wall : scene_.walls) {
      WallPlane plane;
      for (int k = 0; k < 3; ++k) {
        plane.point_m[k] = wall.point_m[k];
        plane.normal[k] = wall.normal[k];
      }
      if (wall.cylinder) plane.radius_m = wall.radius_m;
      if (wall.temperature_K) plane.temperature_K = *wall.temperature_K;
      header.walls.push_back(plane);
    }
    header.periodic.axis = scene_.periodic.axis;
    header.periodic.low_m = scene_.periodic.low_m;
    header.periodic.high_m = scene_.periodic.high_m;
    for (const Probe& probe : scene_.probes)
      header.probes.push_back({probe.name, probe.point_m, probe.radius_m, probe.box_m});
    header.frozen = frozen_;  // the contacts too: fixed after settling (or from the start)
    header.frozen_contacts = contacts_.size();
    writer_.emplace(options_.output_path, header, scene_.output.contacts,
                    options_.overwrite ? ExistingResult::Overwrite : ExistingResult::Refuse);
  }
}

RunOutcome CoupledRun::run() {
  RunOutcome outcome;
  // status: "ok", "failed" or "interrupted"; `message` is printed once as the error line, a
  // later failure while closing the files only when it says something new.
  auto finish = [&](int code, const std::string& message, std::string status) {
    progress_.done();
    // Over MPI rank 0 reports what every process met; another process speaks only for a failure
    // of its own.
    if (!message.empty() && (writes_files_ || local_failure_))
      log_ << (writes_files_ ? "" : "rank " + std::to_string(thermal::MpiWorld::rank()) + ": ")
           << "error: " << message << std::endl;
    auto report = [&](const OutputError& e) {
      // After a failure of the result file, closing it fails for the same reason: one line.
      const bool same_file = code != kExitOk && std::string(e.what()).find(
                                                    "'" + options_.output_path + "'") != std::string::npos;
      if (!same_file) log_ << "error: " << e.what() << std::endl;
      if (code == kExitOk) code = kExitIo, status = "failed";
    };
    summary_.status = status;
    summary_.message = message;
    fill_summary();
    if (writer_ && !writer_->finished()) {
      try {
        writer_->finish(status);
      } catch (const OutputError& e) {
        report(e);
      }
    }
    summary_.status = status;
    // A run refused at start writes nothing, not even a summary; over MPI rank 0 writes it.
    if (!options_.summary_path.empty() && code != kExitInvalid && writes_files_) {
      try {
        summary_.write(options_.summary_path);
      } catch (const OutputError& e) {
        report(e);
      }
    }
    // Over MPI a failure one process may meet alone (rank 0's files, an unexpected exception)
    // would leave the others waiting in their next collective call for ever: all end here.
    if (thermal::MpiWorld::distributed() && (code == kExitIo || local_failure_))
      thermal::MpiWorld::abort(code);
    outcome.exit_code = code;
    outcome.summary = summary_;
    if (integrator_) {
      const auto T = integrator_->temperatures_K();
      outcome.final_temperature_K.assign(T.begin(), T.end());
    }
    return outcome;
  };
  auto failed = [&](int code, const std::string& message) {
    return finish(code, message, code == kExitOk ? "ok" : "failed");
  };

  OutputPaths paths;
  paths.scene = options_.scene_path;
  paths.result = options_.output_path;
  paths.summary = options_.summary_path;
  paths.checkpoint = checkpoint_path_for(options_.output_path);
  paths.checkpoints = true;  // an interruption writes one even without checkpoint_interval
  paths.overwrite = options_.overwrite;
  paths.restart = !options_.restart_path.empty();
  if (thermal::MpiWorld::distributed()) {
    if (const auto why = distributed_heating_refusal(scene_, thermal::MpiWorld::size());
        !why.empty())
      return failed(kExitInvalid, why);
  }
  // Over MPI rank 0 writes every file; the others learn whether it may.
  const auto problem = writes_files_ ? check_output_paths(paths) : OutputPathProblem{};
  if (const int code = thermal::MpiWorld::from_root(problem.exit_code); code != kExitOk)
    return failed(code, problem.message);

  std::optional<Interruption> interruption;
  if (options_.handle_signals) interruption.emplace(options_.quiet);
  try {
    restore_checkpoint();
    prepare_mechanics();
    prepare_thermal();
  } catch (const Interrupted& stop) {
    const int code = stop.signal == SIGINT ? kExitSigint : kExitSigterm;
    RunOutcome result = finish(code, "", "interrupted");
    if (result.exit_code == code)
      log_ << "interrupted by " << signal_name(stop.signal) << " while settling (after "
           << stop.time_s << " s of settle time); no result file written, nothing to resume: "
           << "run the scene again to start over" << std::endl;
    return result;
  } catch (const StartError& e) {
    return failed(kExitInvalid, e.what());
  } catch (const OutputError& e) {
    return failed(kExitIo, e.what());
  } catch (const thermal::ThermalSolverError& e) {
    return failed(kExitSolverFailed, e.what());
  } catch (const std::exception& e) {
    local_failure_ = true;
    return failed(kExitSolverFailed, std::string("setting up the run failed: ") + e.what());
  }

  // Rank 0 opens the result file; over MPI the others must learn whether it could, or they
  // would wait for it for ever in the first step.
  int open_code = kExitOk;
  std::string open_message;
  try {
    if (writes_files_) open_result_file();
  } catch (const ResultMismatch& e) {
    open_code = kExitInvalid, open_message = e.what();
  } catch (const OutputError& e) {
    open_code = kExitIo, open_message = e.what();
  } catch (const std::exception& e) {
    open_code = kExitSolverFailed, open_message = e.what();
  }
  if (const int code = thermal::MpiWorld::from_root(open_code); code != kExitOk)
    return failed(code, open_message);

  try {
    next_checkpoint_s_ = scene_.output.checkpoint_interval_s > 0.0
                             ? next_checkpoint_time_s(t0_, scene_.output.checkpoint_interval_s)
                             : 0.0;
    if (frozen_)
      run_static();
    else if (scene_.effects.mechanics == MechanicsMode::Coupled)
      run_coupled();
    else
      run_dynamic();
  } catch (const Interrupted& stop) {
    const int code = stop.signal == SIGINT ? kExitSigint : kExitSigterm;
    const std::string checkpoint = checkpoint_path_for(options_.output_path);
    RunOutcome result = finish(code, "", "interrupted");
    if (result.exit_code == code) {
      log_ << "interrupted by " << signal_name(stop.signal) << " at t = " << stop.time_s
           << " s; resume with: "
           << (options_.resume_command.empty() ? "tmdem run SCENE -o " + options_.output_path
                                               : options_.resume_command)
           << " --restart " << checkpoint
           << std::endl;
    }
    return result;
  } catch (const thermal::ThermalSolverError& e) {
    return failed(kExitSolverFailed, e.what());
  } catch (const ResultMismatch& e) {
    return failed(writer_ ? kExitIo : kExitInvalid, e.what());
  } catch (const OutputError& e) {
    return failed(kExitIo, e.what());
  } catch (const std::exception& e) {
    local_failure_ = true;
    return failed(kExitSolverFailed, e.what());
  }
  return failed(kExitOk, "");
}

}  // namespace run_detail

RunOutcome run_scene(const Scene& scene, const RunOptions& options, std::ostream& log) {
  run_detail::CoupledRun run(scene, options, log);
  return run.run();
}

}  // namespace tmdem::coupling
