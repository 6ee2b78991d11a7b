#include "coupling/run/ThermalProblem.h"
#include "coupling/run/PackingMeasure.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "coupling/bridge/RestingContacts.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/SceneRestTest.h"
#include "coupling/scene/HeatModes.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

std::string unconverged_step_warning(const std::string& what, double t_s,
                                     const mechanics::NscdIntegrator& nscd,
                                     const mechanics::StepReport& report, double tolerance) {
  std::ostringstream msg;
  msg << "warning: " << what << " at t = " << t_s << " s: contact solver " << nscd.solver().name()
      << (report.stalled ? " stalled (no progress) after " : " did not converge in ")
      << report.sweeps << " iterations (residual " << report.residual << ", tolerance "
      << tolerance << "; Siconos' residual " << report.siconos_residual << ")";
  if (report.retry_parts > 0) {
    msg << ", still after it was retaken";
    if (report.collapse) msg << " at mechanics.fall_tolerance (the bed collapsing)";
    if (report.retry_parts > 1) msg << " in " << report.retry_parts << " parts";
    msg << " (" << report.discarded_sweeps << " sweeps thrown away)";
  }
  return msg.str();
}

SettleSummary settle_packing(mechanics::NscdIntegrator& nscd, const Scene& scene,
                             ProgressReporter& progress, const std::function<bool()>& stop,
                             SettleProgress* state, const SettleCheckpoints* checkpoints) {
  const double h = scene.mechanics.time_step_s;
  const double t_max = scene.mechanics.settle_time_s;
  SettleProgress start;  // afresh, unless `state` says where a settle stands
  if (state) start = *state;
  // This settle's own counts: a study settles the same integrator once per load, and its
  // stats() add up over all of them (a resumed settle: they include its steps before).
  const std::int64_t steps_before = nscd.stats().steps - start.steps;
  const std::int64_t unconverged_before = nscd.stats().unconverged_steps - start.unconverged_steps;
  std::int64_t unconverged = start.unconverged_steps;
  // Warnings: one per unconverged step of h, however many of its parts failed (a resumed
  // settle shows its own first 10).
  const std::int64_t warned_before = nscd.stats().unconverged_time_steps;
  double max_penetration_m = start.max_penetration_m;
  SceneRestTest rest_test(scene, nscd);
  if (!start.rest_window.empty()) rest_test.network().restore_history(std::move(start.rest_window));
  const bool network_test = rest_test.network_test();
  const SettleRestTest& rest = rest_test.network();
  SettleSummary outcome;
  double t = start.time_s;
  // Where the settle stands after the step just taken (finished: at rest or out of time).
  const auto where = [&](SettleProgress& p, bool finished) {
    p.time_s = t;
    p.steps = nscd.stats().steps - steps_before;
    p.unconverged_steps = unconverged;
    p.max_penetration_m = max_penetration_m;
    p.finished = finished;
    p.rest_window = rest.history();
  };
  // Settle time counts steps: t is the same sum of h's whichever step a settle resumed at.
  while (t < t_max - 0.5 * h) {
    const auto report = nscd.step(h);
    // Given up at a signal (Interruption.h): the state is t's; `stop` ends the settle there.
    if (report.interrupted) break;
    t += h;
    unconverged = nscd.stats().unconverged_steps - unconverged_before;
    max_penetration_m = std::max(max_penetration_m, report.max_penetration_m);
    const std::int64_t warned = nscd.stats().unconverged_time_steps - warned_before;
    if (!report.converged && warned <= 10) {
      std::string msg = unconverged_step_warning("settle step", t, nscd, report, report.tolerance);
      if (warned == 10) msg += "; further such warnings are not shown";
      progress.message(msg);
    }
    const double speed = nscd.max_speed();
    const bool at_rest = rest_test.after_step();
    std::ostringstream extra;
    extra << "max speed " << speed << " m/s, " << report.active_contacts << " contacts";
    if (network_test)
      extra << ", force change " << rest.force_change() << ", load speed " << rest.load_speed_m_s()
            << " m/s";
    progress.update("settle", t, t_max, extra.str());
    if (at_rest) {
      outcome.at_rest = true;
      outcome.ended_by = scene.mechanics.rest_test;
      break;
    }
    if (stop && stop()) break;
    if (checkpoints && checkpoints->due()) {
      SettleProgress now;
      where(now, false);
      checkpoints->write(now);
    }
  }
  progress.done();
  if (state) where(*state, outcome.at_rest || !(t < t_max - 0.5 * h));
  outcome.time_s = t;
  outcome.steps = nscd.stats().steps - steps_before;
  outcome.max_speed_m_s = nscd.max_speed();
  outcome.rattlers = rest.rattlers();
  if (const auto packing = measure_packing(scene, nscd.particles())) {
    outcome.bed_height_m = packing->bed_height_m;
    outcome.porosity = packing->porosity;
  }
  // Stopped early (an interrupted run): neither a rest test nor settle_time ended it.
  const bool stopped = !outcome.at_rest && t < t_max - 0.5 * h && stop && stop();
  if (!outcome.at_rest) outcome.ended_by = stopped ? "interrupted" : "settle_time";
  std::ostringstream msg;
  if (stopped) {
    msg << "settle: stopped after " << t << " s (" << outcome.steps << " steps), largest speed "
        << outcome.max_speed_m_s << " m/s";
  } else if (!outcome.at_rest) {
    msg << "warning: not at rest after mechanics.settle_time = " << t_max << " s: ";
    if (network_test)
      msg << "normal forces changed by " << rest.force_change() << " over "
          << scene.mechanics.rest_window << " steps (rest_force_change "
          << scene.mechanics.rest_force_change << "), load carriers' mean speed "
          << rest.load_speed_m_s() << " m/s (settle_velocity "
          << scene.mechanics.settle_velocity_m_per_s << " m/s)";
    else
      msg << "largest speed " << outcome.max_speed_m_s << " m/s (settle_velocity "
          << scene.mechanics.settle_velocity_m_per_s << " m/s)";
    msg << "; freezing the packing as it is (" << outcome.steps << " steps, " << unconverged
        << " unconverged)";
  } else {
    msg << "settle: at rest (" << outcome.ended_by << " test) after " << t << " s ("
        << outcome.steps << " steps, " << nscd.contacts().size() << " contacts, "
        << outcome.rattlers << " rattlers, max penetration " << max_penetration_m << " m, "
        << unconverged << " unconverged steps)";
    if (outcome.porosity)
      msg << "; bed " << *outcome.bed_height_m << " m tall, porosity " << *outcome.porosity
          << " (the box bounding the particles)";
  }
  progress.message(msg.str());
  return outcome;
}

void gather_contacts(const std::vector<mechanics::ContactForce>& forces, ContactList& out) {
  // NscdIntegrator::contacts() already lists its contacts in canonical (i, j) order; a copy in
  // any other order would silently change edge numbering and defeat the values-only updates of
  // DynamicNetwork, so an out-of-order list is a bug worth stopping for (O(C), no allocation).
  out.clear();
  for (std::size_t k = 0; k < forces.size(); ++k) {
    if (k > 0 && !(std::pair(forces[k - 1].i, forces[k - 1].j) < std::pair(forces[k].i, forces[k].j))) {
      std::ostringstream msg;
      msg << "gather_contacts: contacts not in strictly increasing (i, j) order: (" << forces[k - 1].i
          << ", " << forces[k - 1].j << ") before (" << forces[k].i << ", " << forces[k].j << ")";
      throw std::logic_error(msg.str());
    }
    const auto& t = forces[k].tangential_force_N;
    out.add(forces[k].i, forces[k].j, forces[k].normal_force_N, {t.x(), t.y(), t.z()},
            forces[k].dissipated_power_W);
  }
}

namespace {

// Nodes from the scene, edges from `contacts` unless null, the modes the scene switches on.
std::unique_ptr<thermal::ThermalSystem> thermal_system_of(const Scene& scene, ContactList* contacts,
                                                          const mechanics::ParticleSet* geometry) {
  ThermalNetworkBuilder builder(scene);
  auto network = builder.nodes();
  if (contacts) builder.build_edges(*contacts, network, nullptr, geometry);
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> modes;
  for (const auto& name : builder.mode_names(network))
    modes.push_back(thermal::make_heat_transfer_mode(name, builder.mode_settings()));
  return std::make_unique<thermal::ThermalSystem>(std::move(network), std::move(modes));
}

}  // namespace

std::unique_ptr<thermal::ThermalSystem> build_thermal_system(
    const Scene& scene, ContactList& contacts, const mechanics::ParticleSet* geometry) {
  return thermal_system_of(scene, &contacts, geometry);
}

std::unique_ptr<thermal::ThermalSystem> build_thermal_nodes(const Scene& scene) {
  return thermal_system_of(scene, nullptr, nullptr);
}

double max_scene_temperature_K(const Scene& scene) {
  double T_max = 0.0;
  for (const auto& p : scene.particles) T_max = std::max(T_max, p.temperature_K);
  for (const auto& w : scene.walls) {
    if (w.temperature_K) T_max = std::max(T_max, *w.temperature_K);
    for (const auto& [t, T] : w.temperature_table) T_max = std::max(T_max, T);
  }
  return std::max(T_max, max_mode_temperature_K(scene));
}

thermal::IntegratorSettings integrator_settings(const Scene& scene,
                                                thermal::LinearSolverKind linear_solver) {
  thermal::IntegratorSettings s;
  s.linear_solver = linear_solver;
  s.relative_tolerance = scene.thermal.relative_tolerance;
  s.absolute_tolerance_K = scene.thermal.absolute_tolerance_K;
  s.explicit_step_s = scene.thermal.explicit_step_s;
  s.max_temperature_K = max_scene_temperature_K(scene);
  s.stop_at_each_time = scene.effects.mechanics == MechanicsMode::Dynamic ||
                        scene.effects.mechanics == MechanicsMode::Coupled;
  return s;
}

void freeze_packing(const Scene& scene, const mechanics::NscdIntegrator& nscd,
                    FrozenThermalProblem& problem) {
  Scene moved = scene;
  move_scene_walls(moved, nscd.walls());
  problem.contacts.clear();
  gather_contacts(nscd.contacts(), problem.contacts);
  problem.positions_m.clear();
  for (const auto& x : nscd.particles().position) problem.positions_m.push_back({x.x(), x.y(), x.z()});
  problem.wall_points_m.clear();
  for (const auto& w : moved.walls) problem.wall_points_m.push_back(w.point_m);
  problem.system = build_thermal_system(moved, problem.contacts, &nscd.particles());
  problem.T0_K.clear();
  for (const auto& p : scene.particles) problem.T0_K.push_back(p.temperature_K);
}

FrozenThermalProblem build_frozen_thermal_problem(const Scene& scene, ProgressReporter& progress,
                                                  MechanicsStepLog* step_log) {
  FrozenThermalProblem problem;
  switch (scene.effects.mechanics) {
    case MechanicsMode::Off: {
      const auto particles = make_particle_set(scene);
      problem.contacts = resting_contacts(scene, particles);
      for (const auto& x : particles.position) problem.positions_m.push_back({x.x(), x.y(), x.z()});
      for (const auto& w : scene.walls) problem.wall_points_m.push_back(w.point_m);
      problem.system = build_thermal_system(scene, problem.contacts, &particles);
      for (const auto& p : scene.particles) problem.T0_K.push_back(p.temperature_K);
      break;
    }
    case MechanicsMode::Settle: {
      auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
      if (step_log) {
        step_log->attach(*nscd);
        step_log->begin_phase("settle", 0.0);
      }
      problem.settle = settle_packing(*nscd, scene, progress);
      freeze_packing(scene, *nscd, problem);
      break;
    }
    case MechanicsMode::Dynamic:
    case MechanicsMode::Coupled:
      throw std::invalid_argument(
          "the thermal problem of a dynamic or coupled scene changes during the run; it has no "
          "frozen contact graph");
  }
  return problem;
}

}  // namespace tmdem::coupling
