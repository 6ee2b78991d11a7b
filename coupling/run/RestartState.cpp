#include "coupling/run/RestartState.h"

#include <cmath>
#include <string>
#include <utility>

namespace tmdem::coupling {
namespace {

double extra_or_zero(const CheckpointState& cs, const std::string& name) {
  const auto it = cs.extra.find(name);
  return it == cs.extra.end() ? 0.0 : it->second;
}

std::vector<Eigen::Vector3d> vectors_of(const std::vector<double>& flat) {
  std::vector<Eigen::Vector3d> out(flat.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = Eigen::Vector3d(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return out;
}

std::vector<double> flat_of(const std::vector<Eigen::Vector3d>& vectors) {
  std::vector<double> out;
  out.reserve(3 * vectors.size());
  for (const auto& v : vectors) out.insert(out.end(), {v.x(), v.y(), v.z()});
  return out;
}

}  // namespace

void store_contacts(const ContactList& contacts, double time_step_s, CheckpointState& cs) {
  cs.contact_pair = contacts.pair;
  cs.contact_normal_force_N = contacts.normal_force_N;
  cs.contact_tangential_force_N = contacts.tangential_force_N;
  // Kept for readers of the older layout: the normal impulse over one mechanics step.
  cs.contact_impulse_N_s.clear();
  for (double F : contacts.normal_force_N) cs.contact_impulse_N_s.insert(cs.contact_impulse_N_s.end(), {F * time_step_s, 0.0, 0.0});
}

ContactList contacts_of(const CheckpointState& cs, double time_step_s) {
  ContactList contacts;
  const auto& tangential = cs.contact_tangential_force_N;
  for (std::size_t c = 0; c < cs.contact_pair.size() / 2; ++c) {
    const double normal_N = cs.contact_normal_force_N.empty() ? cs.contact_impulse_N_s[3 * c] / time_step_s
                                                              : cs.contact_normal_force_N[c];
    contacts.add(cs.contact_pair[2 * c], cs.contact_pair[2 * c + 1], normal_N,
                 {tangential[3 * c], tangential[3 * c + 1], tangential[3 * c + 2]});
  }
  return contacts;
}

// The integrator's counters and their /extra names.
constexpr std::pair<const char*, long thermal::IntegratorStats::*> kThermalCounters[] = {
    {"thermal_steps", &thermal::IntegratorStats::steps},
    {"thermal_rhs_evals", &thermal::IntegratorStats::rhs_evals},
    {"thermal_jacobian_evals", &thermal::IntegratorStats::jacobian_evals},
    {"thermal_linear_setups", &thermal::IntegratorStats::linear_setups},
    {"thermal_linear_iterations", &thermal::IntegratorStats::linear_iterations},
    {"thermal_error_test_failures", &thermal::IntegratorStats::error_test_failures},
    {"thermal_convergence_failures", &thermal::IntegratorStats::convergence_failures},
    {"thermal_reinitializations", &thermal::IntegratorStats::reinitializations},
};

void store_thermal_stats(const thermal::IntegratorStats& s, CheckpointState& cs) {
  for (const auto& [name, counter] : kThermalCounters) cs.extra[name] = double(s.*counter);
}

thermal::IntegratorStats thermal_stats_of(const CheckpointState& cs) {
  thermal::IntegratorStats s;
  for (const auto& [name, counter] : kThermalCounters) s.*counter = long(extra_or_zero(cs, name));
  return s;
}

void store_mechanics_stats(const mechanics::MechanicsStats& s, CheckpointState& cs) {
  cs.extra["mechanics_steps"] = double(s.steps);
  cs.extra["mechanics_total_sweeps"] = double(s.total_sweeps);
  cs.extra["mechanics_max_sweeps"] = double(s.max_sweeps);
  cs.extra["mechanics_unconverged_steps"] = double(s.unconverged_steps);
  cs.extra["mechanics_stalled_steps"] = double(s.stalled_steps);
  cs.extra["mechanics_fall_steps"] = double(s.fall_steps);
  cs.extra["mechanics_fall_unconverged_steps"] = double(s.fall_unconverged_steps);
  cs.extra["mechanics_collapse_steps"] = double(s.collapse_steps);
  cs.extra["mechanics_max_penetration_m"] = s.max_penetration_m;
  cs.extra["mechanics_correction_sweeps"] = double(s.correction_sweeps);
  cs.extra["mechanics_halved_steps"] = double(s.halved_steps);
  cs.extra["mechanics_landing_halved_steps"] = double(s.landing_halved_steps);
  cs.extra["mechanics_retried_steps"] = double(s.retried_steps);
  cs.extra["mechanics_discarded_sweeps"] = double(s.discarded_sweeps);
  cs.extra["mechanics_kept_parts_steps"] = double(s.kept_parts_steps);
  cs.extra["mechanics_relisted_steps"] = double(s.relisted_steps);
  cs.extra["mechanics_fallback_solves"] = double(s.fallback.solves);
  cs.extra["mechanics_fallback_converged_by_second"] = double(s.fallback.converged_by_second);
  cs.extra["mechanics_fallback_converged_by_first_again"] = double(s.fallback.converged_by_first_again);
  cs.extra["mechanics_fallback_converged_by_sweeps"] = double(s.fallback.converged_by_sweeps);
  cs.extra["mechanics_fallback_within_when_handed_on"] = double(s.fallback.within_when_handed_on);
  cs.extra["mechanics_fallback_sweeps"] = double(s.fallback.sweeps);
  cs.extra["mechanics_fallback_first_sweeps"] = double(s.fallback.first_sweeps);
  cs.extra["mechanics_unconverged_time_steps"] = double(s.unconverged_time_steps);
  cs.extra["mechanics_piston_corrections"] = double(s.piston_corrections);
  cs.extra["mechanics_last_step_s"] = s.last_step_s;
  cs.extra["mechanics_correction_potential_J"] = s.correction_potential_J;
  cs.extra["mechanics_max_travel_m"] = s.max_travel_m;
  cs.extra["mechanics_max_siconos_residual"] = s.max_siconos_residual;
  cs.extra["mechanics_siconos_unconverged_steps"] = double(s.siconos_unconverged_steps);
  cs.extra["mechanics_max_natural_map_residual"] = s.max_natural_map_residual;
  cs.extra["mechanics_energy_change_J"] = s.energy_change_J;
  cs.extra["mechanics_contact_dissipation_J"] = s.contact_dissipation_J;
  cs.extra["mechanics_numerical_dissipation_J"] = s.numerical_dissipation_J;
}

mechanics::MechanicsStats mechanics_stats_of(const CheckpointState& cs) {
  mechanics::MechanicsStats s;
  s.steps = std::int64_t(extra_or_zero(cs, "mechanics_steps"));
  s.total_sweeps = std::int64_t(extra_or_zero(cs, "mechanics_total_sweeps"));
  s.max_sweeps = int(extra_or_zero(cs, "mechanics_max_sweeps"));
  s.unconverged_steps = std::int64_t(extra_or_zero(cs, "mechanics_unconverged_steps"));
  s.stalled_steps = std::int64_t(extra_or_zero(cs, "mechanics_stalled_steps"));
  s.fall_steps = std::int64_t(extra_or_zero(cs, "mechanics_fall_steps"));
  s.fall_unconverged_steps = std::int64_t(extra_or_zero(cs, "mechanics_fall_unconverged_steps"));
  s.collapse_steps = std::int64_t(extra_or_zero(cs, "mechanics_collapse_steps"));
  s.max_penetration_m = extra_or_zero(cs, "mechanics_max_penetration_m");
  s.correction_sweeps = std::int64_t(extra_or_zero(cs, "mechanics_correction_sweeps"));
  s.halved_steps = std::int64_t(extra_or_zero(cs, "mechanics_halved_steps"));
  s.landing_halved_steps = std::int64_t(extra_or_zero(cs, "mechanics_landing_halved_steps"));
  s.retried_steps = std::int64_t(extra_or_zero(cs, "mechanics_retried_steps"));
  s.discarded_sweeps = std::int64_t(extra_or_zero(cs, "mechanics_discarded_sweeps"));
  s.kept_parts_steps = std::int64_t(extra_or_zero(cs, "mechanics_kept_parts_steps"));
  s.relisted_steps = std::int64_t(extra_or_zero(cs, "mechanics_relisted_steps"));
  s.fallback.solves = std::int64_t(extra_or_zero(cs, "mechanics_fallback_solves"));
  s.fallback.converged_by_second = std::int64_t(extra_or_zero(cs, "mechanics_fallback_converged_by_second"));
  s.fallback.converged_by_first_again = std::int64_t(extra_or_zero(cs, "mechanics_fallback_converged_by_first_again"));
  s.fallback.converged_by_sweeps = std::int64_t(extra_or_zero(cs, "mechanics_fallback_converged_by_sweeps"));
  s.fallback.within_when_handed_on = std::int64_t(extra_or_zero(cs, "mechanics_fallback_within_when_handed_on"));
  s.fallback.sweeps = std::int64_t(extra_or_zero(cs, "mechanics_fallback_sweeps"));
  s.fallback.first_sweeps = std::int64_t(extra_or_zero(cs, "mechanics_fallback_first_sweeps"));
  s.unconverged_time_steps = std::int64_t(extra_or_zero(cs, "mechanics_unconverged_time_steps"));
  s.piston_corrections = std::int64_t(extra_or_zero(cs, "mechanics_piston_corrections"));
  s.last_step_s = extra_or_zero(cs, "mechanics_last_step_s");
  s.correction_potential_J = extra_or_zero(cs, "mechanics_correction_potential_J");
  s.max_travel_m = extra_or_zero(cs, "mechanics_max_travel_m");
  s.max_siconos_residual = extra_or_zero(cs, "mechanics_max_siconos_residual");
  s.siconos_unconverged_steps = std::int64_t(extra_or_zero(cs, "mechanics_siconos_unconverged_steps"));
  s.max_natural_map_residual = extra_or_zero(cs, "mechanics_max_natural_map_residual");
  s.energy_change_J = extra_or_zero(cs, "mechanics_energy_change_J");
  s.contact_dissipation_J = extra_or_zero(cs, "mechanics_contact_dissipation_J");
  s.numerical_dissipation_J = extra_or_zero(cs, "mechanics_numerical_dissipation_J");
  return s;
}

void store_mechanics_state(const mechanics::MechanicsState& m, CheckpointState& cs) {
  cs.position_m = flat_of(m.position_m);
  cs.velocity_m_per_s = flat_of(m.velocity_m_per_s);
  cs.angular_velocity_rad_per_s = flat_of(m.angular_velocity_rad_per_s);
  cs.has_mechanics = true;
  cs.detector_margin_m = m.margin_m;
  cs.detector_wall_margin_m = m.wall_margin_m;
  // 1 when a landing wall set the table's margin (0 in checkpoints older than it).
  cs.extra["mechanics_margin_widened_by_wall"] = m.margin_widened_by_wall ? 1.0 : 0.0;
  cs.detector_rebuilds = m.rebuilds;
  cs.detector_reference_position_m = flat_of(m.reference_position_m);
  cs.candidate_pair.clear();
  for (const auto& p : m.candidates) cs.candidate_pair.insert(cs.candidate_pair.end(), {p.i, p.j});
  cs.candidate_force_N = flat_of(m.candidate_force_N);
  cs.candidate_rolling_torque_Nm = flat_of(m.candidate_rolling_torque_Nm);
  cs.candidate_held_overlap_m = m.candidate_held_overlap_m;
  cs.contact_solver_state = m.solver_state;
  cs.wall_point_m = flat_of(m.wall_point_m);
  cs.wall_velocity_m_per_s = m.wall_velocity_m_per_s;
  cs.detector_reference_wall_point_m = flat_of(m.reference_wall_point_m);
  store_mechanics_stats(m.stats, cs);
  // The tolerance schedule's phase (0 before the fall, also in checkpoints older than it).
  cs.extra["mechanics_tolerance_phase"] = double(int(m.tolerance_schedule.phase));
  cs.extra["mechanics_tolerance_landed_step"] = double(m.tolerance_schedule.landed_step);
  cs.extra["mechanics_retry_limit"] = double(m.retry_limit);
  cs.extra["mechanics_retry_converged_steps"] = double(m.retry_converged_in_a_row);
  cs.extra["mechanics_start_parts"] = double(m.start_parts);
  cs.extra["mechanics_start_parts_converged_steps"] = double(m.start_parts_converged_in_a_row);
}

mechanics::MechanicsState mechanics_state_of(const CheckpointState& cs) {
  mechanics::MechanicsState m;
  m.position_m = vectors_of(cs.position_m);
  m.velocity_m_per_s = vectors_of(cs.velocity_m_per_s);
  m.angular_velocity_rad_per_s = vectors_of(cs.angular_velocity_rad_per_s);
  m.margin_m = cs.detector_margin_m;
  m.wall_margin_m = cs.detector_wall_margin_m;
  m.margin_widened_by_wall = extra_or_zero(cs, "mechanics_margin_widened_by_wall") != 0.0;
  m.rebuilds = cs.detector_rebuilds;
  m.reference_position_m = vectors_of(cs.detector_reference_position_m);
  for (std::size_t k = 0; k + 1 < cs.candidate_pair.size(); k += 2)
    m.candidates.push_back({std::int32_t(cs.candidate_pair[k]), std::int32_t(cs.candidate_pair[k + 1])});
  m.candidate_force_N = vectors_of(cs.candidate_force_N);
  m.candidate_rolling_torque_Nm = vectors_of(cs.candidate_rolling_torque_Nm);
  m.candidate_held_overlap_m = cs.candidate_held_overlap_m;
  m.solver_state = cs.contact_solver_state;
  m.wall_point_m = vectors_of(cs.wall_point_m);
  m.wall_velocity_m_per_s = cs.wall_velocity_m_per_s;
  m.reference_wall_point_m = vectors_of(cs.detector_reference_wall_point_m);
  m.stats = mechanics_stats_of(cs);
  m.tolerance_schedule.phase =
      mechanics::ToleranceSchedule::Phase(int(extra_or_zero(cs, "mechanics_tolerance_phase")));
  m.tolerance_schedule.landed_step =
      std::int64_t(extra_or_zero(cs, "mechanics_tolerance_landed_step"));
  m.retry_limit = int(extra_or_zero(cs, "mechanics_retry_limit"));
  m.retry_converged_in_a_row = int(extra_or_zero(cs, "mechanics_retry_converged_steps"));
  m.start_parts = int(extra_or_zero(cs, "mechanics_start_parts"));
  m.start_parts_converged_in_a_row = int(extra_or_zero(cs, "mechanics_start_parts_converged_steps"));
  return m;
}

void store_settle_progress(const SettleProgress& p, CheckpointState& cs) {
  cs.settling = true;
  cs.extra["settle_progress_time_s"] = p.time_s;
  cs.extra["settle_progress_steps"] = double(p.steps);
  cs.extra["settle_progress_unconverged_steps"] = double(p.unconverged_steps);
  cs.extra["settle_progress_max_penetration_m"] = p.max_penetration_m;
  cs.settle_window_contacts.clear();
  cs.settle_window_pair.clear();
  cs.settle_window_normal_force_N.clear();
  for (const auto& snapshot : p.rest_window) {
    cs.settle_window_contacts.push_back(std::int64_t(snapshot.pair.size()));
    for (const auto& [i, j] : snapshot.pair) cs.settle_window_pair.insert(cs.settle_window_pair.end(), {i, j});
    cs.settle_window_normal_force_N.insert(cs.settle_window_normal_force_N.end(),
                                           snapshot.normal_force_N.begin(), snapshot.normal_force_N.end());
  }
}

SettleProgress settle_progress_of(const CheckpointState& cs) {
  SettleProgress p;
  p.time_s = extra_or_zero(cs, "settle_progress_time_s");
  p.steps = std::llround(extra_or_zero(cs, "settle_progress_steps"));
  p.unconverged_steps = std::llround(extra_or_zero(cs, "settle_progress_unconverged_steps"));
  p.max_penetration_m = extra_or_zero(cs, "settle_progress_max_penetration_m");
  std::size_t at = 0;  // the next contact of the flat lists
  for (const std::int64_t count : cs.settle_window_contacts) {
    SettleRestTest::Snapshot snapshot;
    for (std::int64_t k = 0; k < count; ++k, ++at) {
      snapshot.pair.emplace_back(cs.settle_window_pair[2 * at], cs.settle_window_pair[2 * at + 1]);
      snapshot.normal_force_N.push_back(cs.settle_window_normal_force_N[at]);
    }
    p.rest_window.push_back(std::move(snapshot));
  }
  return p;
}

double next_checkpoint_time_s(double t_s, double interval_s) {
  // k interval with k the count of whole intervals reached (1e-9 absorbs t = k interval
  // computed with round-off), plus one.
  return interval_s * (std::floor(t_s / interval_s + 1e-9) + 1.0);
}

}  // namespace tmdem::coupling
