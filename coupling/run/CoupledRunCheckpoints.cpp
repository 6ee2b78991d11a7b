// CoupledRun's checkpoints, restarts and interruptions (docs/restart-and-files.md "Restart, interruption and
// files"): every checkpoint time is an integration boundary, in the run that writes the
// checkpoint and in the run restarted from it.
#include <cmath>
#include <filesystem>
#include <string>
#include <system_error>

#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/RestartState.h"
#include "coupling/scene/SceneDifference.h"

namespace tmdem::coupling::run_detail {

void CoupledRun::restore_checkpoint() {
  if (options_.restart_path.empty()) return;
  if (!restart_) restart_ = read_checkpoint(options_.restart_path);  // OutputError -> exit 4
  const std::size_t n = scene_.particles.size();
  if (restart_->temperature_K.size() != n)
    throw StartError("checkpoint " + options_.restart_path + " holds " +
                     std::to_string(restart_->temperature_K.size()) +
                     " particles but the scene has " + std::to_string(n));
  // A restart continues the same physics: only the duration and the output may change.
  if (const auto difference = first_scene_difference(restart_->scene_toml, scene_.resolved_toml))
    throw StartError("restart refused: key " + difference->key +
                     " differs from the scene in checkpoint " + options_.restart_path +
                     " (checkpoint " + difference->before_value + ", now " +
                     difference->after_value +
                     "); a restart may change only simulation.duration and output.*");
  // A settle checkpoint: the run starts afresh at t = 0 and resumes settling from it
  // (prepare_mechanics); nothing of a thermal run is in it yet.
  if (restart_->settling) {
    if (!restart_->has_mechanics)
      throw StartError("settle checkpoint " + options_.restart_path + " holds no mechanics state");
    settle_resume_ = std::move(restart_);
    restart_.reset();
    // Resumed from the very file this run's checkpoints go to: removed as any settle checkpoint
    // of the run once it completes (kept while a thermal checkpoint has not replaced it).
    std::error_code error;
    settle_checkpoint_on_disk_ =
        std::filesystem::equivalent(options_.restart_path, checkpoint_path_for(options_.output_path), error);
    return;
  }
  t0_ = restart_->time_s;
  T0_ = restart_->temperature_K;
  boundary_heat0_J_ = restart_->boundary_heat_J;
  if (auto it = restart_->extra.find("initial_energy_J"); it != restart_->extra.end())
    initial_energy_J_ = it->second;
  if (auto it = restart_->extra.find("contact_heat_J"); it != restart_->extra.end())
    contact_heat_J_ = it->second;
  if (auto it = restart_->extra.find("dissipation_share_J"); it != restart_->extra.end())
    dissipation_share_J_ = it->second;
  if (auto it = restart_->extra.find("dissipation_received_J"); it != restart_->extra.end())
    dissipation_received0_J_ = it->second;
  // A restarted settle run does not settle again: it reports how the checkpointed run settled.
  const auto& extra = restart_->extra;
  if (auto it = extra.find("coupled_couplings"); it != extra.end()) {
    thermo_.couplings = std::llround(it->second);
    thermo_.steps = std::llround(extra.at("coupled_steps"));
    thermo_.not_at_rest = std::llround(extra.at("coupled_not_at_rest"));
    for (std::size_t w = 0;; ++w) {
      const auto force = extra.find("coupled_largest_wall_force_N_" + std::to_string(w));
      if (force == extra.end()) break;
      thermo_.largest_wall_force_N.push_back(force->second);
    }
  }
  if (extra.contains("settle_at_rest") && extra.contains("settle_time_s") &&
      extra.contains("settle_steps") && extra.contains("settle_max_speed_m_s")) {
    summary_.settle = SettleSummary{extra.at("settle_at_rest") != 0.0, extra.at("settle_time_s"),
                                    std::llround(extra.at("settle_steps")),
                                    extra.at("settle_max_speed_m_s"), "settle_time", 0, std::nullopt, std::nullopt};
    if (auto it = extra.find("settle_rattlers"); it != extra.end())
      summary_.settle->rattlers = std::llround(it->second);
    if (extra.contains("settle_porosity") && extra.contains("settle_bed_height_m")) {
      summary_.settle->bed_height_m = extra.at("settle_bed_height_m");
      summary_.settle->porosity = extra.at("settle_porosity");
    }
    if (auto it = extra.find("settle_ended_by"); it != extra.end())
      summary_.settle->ended_by = it->second == 1.0   ? "network"
                                  : it->second == 2.0 ? "velocity"
                                                      : "settle_time";
  }
}

void CoupledRun::maybe_checkpoint(double t_s) {
  if (!(scene_.output.checkpoint_interval_s > 0.0) || t_s < next_checkpoint_s_ - 1e-12) return;
  next_checkpoint_s_ = next_checkpoint_time_s(t_s, scene_.output.checkpoint_interval_s);
  checkpoint(t_s);
}

// An integration boundary (docs/restart-and-files.md "Restart, interruption and files"): the thermal integrator
// starts afresh from the checkpoint's temperatures, boundary heat and counters. The run that
// writes the checkpoint does this right after writing it, a run restarted from it does the same
// at its start, so both continue identically.
void CoupledRun::begin_thermal_segment(const CheckpointState& cs) {
  integrator_->initialize(cs.time_s, cs.temperature_K, cs.boundary_heat_J);
  auto stats = thermal_stats_of(cs);
  ++stats.reinitializations;
  integrator_->restore_stats(stats);
}

void CoupledRun::checkpoint(double t_s) {
  CheckpointState cs;
  cs.time_s = t_s;
  if (nscd_ && !frozen_) {
    store_mechanics_state(nscd_->save_state(), cs);
  } else {
    const auto x = positions();
    cs.position_m.assign(x.begin(), x.end());
    cs.velocity_m_per_s.assign(cs.position_m.size(), 0.0);
    cs.angular_velocity_rad_per_s.assign(cs.position_m.size(), 0.0);
    if (nscd_) {
      store_mechanics_stats(nscd_->stats(), cs);
      // Where settling left the walls (a piston came to rest on the bed): a restart's gaps.
      for (const auto& wall : scene_.walls)
        cs.settled_wall_point_m.insert(cs.settled_wall_point_m.end(), wall.point_m.begin(), wall.point_m.end());
    }
  }
  const auto T = integrator_->temperatures_K();
  cs.temperature_K.assign(T.begin(), T.end());
  cs.boundary_heat_J = integrator_->boundary_heat_J();
  cs.scene_toml = scene_.resolved_toml;
  if (writes_files_) {
    writer_->flush();  // the checkpoint counts frames the .h5 holds
    cs.frames_written = std::int64_t(writer_->stored_frames());
    cs.result_contact_tail = writer_->contact_tail();
  }
  // Empty over MPI when each process built only its piece of the bed (no process holds every
  // contact); a frozen bed without mechanics detects them again on restart.
  store_contacts(contacts_, scene_.mechanics.time_step_s, cs);
  if (dynamic_network_) cs.thermal_pattern_pair = dynamic_network_->pattern_pairs();
  store_thermal_stats(integrator_->stats(), cs);
  cs.extra["initial_energy_J"] = initial_energy_J_;
  cs.extra["contact_heat_J"] = contact_heat_J_;
  // The thermal segment restarts below: its integral of the dissipation share moves to the run.
  dissipation_received0_J_ += integrator_->dissipation_heat_J();
  cs.extra["dissipation_share_J"] = dissipation_share_J_;
  cs.extra["dissipation_received_J"] = dissipation_received0_J_;
  if (expansion_) {  // a coupled run: the radii of its last coupling, and its couplings so far
    const auto& radius = nscd_->particles().radius;
    cs.radius_m.assign(radius.begin(), radius.end());
    cs.extra["coupled_couplings"] = double(thermo_.couplings);
    cs.extra["coupled_steps"] = double(thermo_.steps);
    cs.extra["coupled_not_at_rest"] = double(thermo_.not_at_rest);
    for (std::size_t w = 0; w < thermo_.largest_wall_force_N.size(); ++w)
      cs.extra["coupled_largest_wall_force_N_" + std::to_string(w)] = thermo_.largest_wall_force_N[w];
  }
  if (summary_.settle) {
    cs.extra["settle_at_rest"] = summary_.settle->at_rest ? 1.0 : 0.0;
    cs.extra["settle_time_s"] = summary_.settle->time_s;
    cs.extra["settle_steps"] = double(summary_.settle->steps);
    cs.extra["settle_max_speed_m_s"] = summary_.settle->max_speed_m_s;
    cs.extra["settle_rattlers"] = double(summary_.settle->rattlers);
    if (summary_.settle->porosity) {
      cs.extra["settle_bed_height_m"] = *summary_.settle->bed_height_m;
      cs.extra["settle_porosity"] = *summary_.settle->porosity;
    }
    cs.extra["settle_ended_by"] = summary_.settle->ended_by == "network"    ? 1.0
                                  : summary_.settle->ended_by == "velocity" ? 2.0
                                                                            : 0.0;
  }
  if (writes_files_) {
    const auto output_start = std::chrono::steady_clock::now();
    write_checkpoint(checkpoint_path_for(options_.output_path), cs);
    output_seconds_ += seconds_since(output_start);
    settle_checkpoint_on_disk_ = false;
  }
  last_checkpoint_s_ = t_s;
  begin_thermal_segment(cs);
}

void CoupledRun::checkpoint_settle(const SettleProgress& where) {
  CheckpointState cs;
  cs.time_s = 0.0;  // before the thermal run: nothing of it has happened yet
  store_mechanics_state(nscd_->save_state(), cs);
  for (const auto& p : scene_.particles) cs.temperature_K.push_back(p.temperature_K);
  cs.scene_toml = scene_.resolved_toml;
  store_settle_progress(where, cs);
  if (writes_files_) {
    const auto output_start = std::chrono::steady_clock::now();
    write_checkpoint(checkpoint_path_for(options_.output_path), cs);
    output_seconds_ += seconds_since(output_start);
    settle_checkpoint_on_disk_ = true;
  }
}

void CoupledRun::stop_if_interrupted(double t_s, bool frame_written) {
  const int signal = Interruption::pending();
  if (signal == 0 || t_s >= scene_.duration_s) return;  // at the end: the run is complete
  if (!frame_written) write_frame(t_s);
  if (last_checkpoint_s_ != t_s) checkpoint(t_s);
  throw Interrupted{signal, t_s};
}

}  // namespace tmdem::coupling::run_detail
