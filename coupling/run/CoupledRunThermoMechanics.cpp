// The "coupled" run (effects.mechanics = "coupled"; CoupledRun.h): after the settle, the heating
// goes from coupling to coupling (every mechanics.coupling_interval, at each point of a wall
// temperature table inside the run, and at the end); at each,
// the particles take the radii of their temperatures (ThermalExpansion.h), the packing is
// settled again quasi-statically (the heating paused: mechanical time is not heating time), and
// the thermal network takes the new contacts and forces (DynamicNetwork), the integrator
// re-initialised from the temperatures reached. Frames fall between couplings as in every
// run; each carries the walls' points, and the summary the walls' forces.
#include <algorithm>
#include <cmath>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/output/WallForces.h"
#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/ThermalProblem.h"

namespace tmdem::coupling::run_detail {

void CoupledRun::run_coupled() {
  const double interval = scene_.mechanics.coupling_interval_s;
  const double end = scene_.duration_s;
  if (!restart_) {
    // The settled network as the dynamic network's first pattern (as a dynamic run's steps do).
    dynamic_network_->update(contacts_, *integrator_, CouplingStrategy::Restart, &nscd_->particles());
    track_wall_forces();
    write_frame(0.0);
  }
  const auto frames = frame_times();
  // Couplings: every interval, at the end, and where a wall temperature table changes slope
  // (its points inside the run): the heating turns there, and the packing follows.
  std::vector<double> couple_at;
  for (long k = 1; double(k) * interval < end; ++k) couple_at.push_back(double(k) * interval);
  couple_at.push_back(end);
  for (const auto& wall : scene_.walls)
    for (const auto& point : wall.temperature_table)
      if (point[0] > 0.0 && point[0] < end) couple_at.push_back(point[0]);
  std::sort(couple_at.begin(), couple_at.end());
  const double tiny = 1e-9 * std::min(interval, scene_.output.interval_s);
  couple_at.erase(std::unique(couple_at.begin(), couple_at.end(),
                              [tiny](double a, double b) { return b - a <= tiny; }),
                  couple_at.end());
  // Past the start (t0_ > 0 on a restart: its frames and couplings up to t0_ were done before
  // the checkpoint, which came after them).
  std::size_t next_frame = 0, next_coupling = 0;
  while (next_frame < frames.size() && frames[next_frame] <= t0_ + tiny) ++next_frame;
  while (next_coupling < couple_at.size() && couple_at[next_coupling] <= t0_ + tiny) ++next_coupling;
  while (next_frame < frames.size()) {
    const double coupling_time = couple_at[std::min(next_coupling, couple_at.size() - 1)];
    const double frame_time = frames[next_frame];
    const double t = std::min(coupling_time, frame_time);
    const auto thermal_start = std::chrono::steady_clock::now();
    integrator_->advance_to(t);
    thermal_seconds_ += seconds_since(thermal_start);
    if (next_coupling < couple_at.size() && std::abs(t - coupling_time) <= tiny) {
      recouple();
      ++next_coupling;
    }
    bool frame_written = false;
    if (std::abs(t - frame_time) <= tiny) {
      track_wall_forces();
      write_frame(t);
      frame_written = true;
      ++next_frame;
      maybe_checkpoint(t);  // at frames, as every run: integration boundaries of both runs
    }
    stop_if_interrupted(t, frame_written);
    progress_.update("run", t, end, std::to_string(thermo_.couplings) + " couplings");
  }
}

void CoupledRun::recouple() {
  const auto mechanics_start = std::chrono::steady_clock::now();
  if (expansion_->any()) {
    expansion_->radii(integrator_->temperatures_K(), radius_m_);
    auto& particles = nscd_->particles();
    std::copy(radius_m_.begin(), radius_m_.end(), particles.radius.begin());
    nscd_->invalidate_contacts();  // candidates and gaps follow the radii
  }
  if (step_log_) step_log_->begin_phase("resettle", 0.0);
  const SettleSummary settled =
      settle_packing(*nscd_, scene_, progress_, &Interruption::requested);
  mechanics_seconds_ += seconds_since(mechanics_start);
  ++thermo_.couplings;
  thermo_.steps += settled.steps;
  if (!settled.at_rest) ++thermo_.not_at_rest;
  gather_contacts(nscd_->contacts(), contacts_);
  move_scene_walls(scene_, nscd_->walls());
  const auto thermal_start = std::chrono::steady_clock::now();
  // Re-initialised at every coupling whatever thermal.coupling says: couplings are rare, and
  // with the history kept across a jump of the conductances the energy balance held only to the
  // integrator's tolerance (1.5e-6 on a heated row of spheres, 1.2e-16 re-initialised).
  dynamic_network_->update(contacts_, *integrator_, CouplingStrategy::Restart, &nscd_->particles());
  thermal_seconds_ += seconds_since(thermal_start);
}

void CoupledRun::track_wall_forces() {
  const std::size_t walls = scene_.walls.size();
  thermo_.last_wall_force_N.resize(walls);
  sum_wall_forces(contacts_.pair, contacts_.normal_force_N, thermo_.last_wall_force_N);
  thermo_.largest_wall_force_N.resize(walls, 0.0);
  for (std::size_t w = 0; w < walls; ++w)
    thermo_.largest_wall_force_N[w] = std::max(thermo_.largest_wall_force_N[w], thermo_.last_wall_force_N[w]);
  thermo_.last_wall_point_m.clear();
  for (const auto& wall : scene_.walls)
    thermo_.last_wall_point_m.insert(thermo_.last_wall_point_m.end(), wall.point_m.begin(), wall.point_m.end());
}

}  // namespace tmdem::coupling::run_detail
