// CoupledRun's time loops (CoupledRun.h describes the run): on a frozen contact graph
// (mechanics off or settled) the thermal side advances from frame to frame; in a dynamic run
// every mechanical step hands its contacts over and the thermal side follows over that step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/HeatModes.h"

namespace tmdem::coupling::run_detail {

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
  // Whether the result holds a frame at t (a restart's file: when t0 is a frame time).
  bool frame_at_t = !restart_;
  for (const double frame_s : times) frame_at_t = frame_at_t || std::abs(frame_s - t0_) < 0.5 * h;
  long k = std::lround(t0_ / h);
  if (step_log_) step_log_->begin_phase("run", t0_);
  while (t < scene_.duration_s - 1e-9 * h) {
    ++k;
    const double t_next = std::min(double(k) * h, scene_.duration_s);
    const auto mechanics_start = std::chrono::steady_clock::now();
    const auto report = nscd_->step(t_next - t);
    mechanics_seconds_ += seconds_since(mechanics_start);
    if (report.interrupted) {
      // Given up at a signal (Interruption.h): the state is t's, the last frame and checkpoint too.
      stop_if_interrupted(t, frame_at_t);
      throw std::logic_error("mechanics step at t = " + std::to_string(t_next) + " s given up without a signal");
    }
    // One warning per unconverged step of h, however many of its parts failed.
    if (!report.converged && !options_.quiet && nscd_->stats().unconverged_time_steps <= 10) {
      std::string msg = unconverged_step_warning("mechanics step", t_next, *nscd_, report,
                                                 report.tolerance);
      if (nscd_->stats().unconverged_time_steps == 10) msg += "; further such warnings are not shown";
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
    frame_at_t = frame_written;
    progress_.update("run", t, scene_.duration_s,
                     std::to_string(contacts_.size()) + " contacts");
  }
}

}  // namespace tmdem::coupling::run_detail
