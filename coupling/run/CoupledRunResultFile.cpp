// CoupledRun's result file (CoupledRun.h describes the run): created with the scene's header,
// or reopened to resume from a checkpoint, and one frame written at each output time (rank 0
// alone over MPI).
#include <chrono>
#include <filesystem>
#include <system_error>

#include "coupling/bridge/ContactHeatFlow.h"
#include "coupling/bridge/ContactSeriesFactors.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/CoupledRunLoop.h"

namespace tmdem::coupling::run_detail {

std::span<const double> CoupledRun::positions() const {
  if (!centre_m_.empty()) return centre_m_;  // over MPI, each process its piece of the bed
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

void CoupledRun::open_result_file() {
  if (restart_) {
    // A restart into another file (output.* may differ from the checkpoint's: -o names a result
    // that does not exist yet): the checkpoint's own result is copied there and continued; the
    // original keeps its frames. Reopening checks the copy as it checks any result.
    std::error_code error;
    if (const std::string source = result_path_for_checkpoint(options_.restart_path);
        !source.empty() && !std::filesystem::exists(options_.output_path, error) &&
        std::filesystem::exists(source, error)) {
      if (!std::filesystem::copy_file(source, options_.output_path, error))
        throw OutputError("cannot copy result file '" + source + "' to '" + options_.output_path +
                          "' to continue it there: " + error.message());
    }
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

}  // namespace tmdem::coupling::run_detail
