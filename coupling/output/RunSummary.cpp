#include "coupling/output/RunSummary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <utility>

namespace tmdem::coupling {
namespace {

// Numbers that were NaN or infinite are written as null by nlohmann::json; read them back as NaN.
double number(const nlohmann::json& object, const char* key, double fallback) {
  if (!object.contains(key)) return fallback;
  const nlohmann::json& value = object.at(key);
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  return value.get<double>();
}

std::int64_t integer(const nlohmann::json& object, const char* key, std::int64_t fallback) {
  return object.contains(key) ? object.at(key).get<std::int64_t>() : fallback;
}

std::string text(const nlohmann::json& object, const char* key, const std::string& fallback) {
  return object.contains(key) ? object.at(key).get<std::string>() : fallback;
}

const nlohmann::json& section(const nlohmann::json& object, const char* key) {
  static const nlohmann::json empty = nlohmann::json::object();
  return object.contains(key) ? object.at(key) : empty;
}

// mechanics.tolerance_schedule's numbers and counts, by key (tightened_* are null until set).
constexpr std::pair<const char*, double ToleranceScheduleSummary::*> kScheduleNumbers[] = {
    {"tolerance", &ToleranceScheduleSummary::tolerance},
    {"fall_tolerance", &ToleranceScheduleSummary::fall_tolerance},
    {"fall_speed_m_s", &ToleranceScheduleSummary::fall_speed_m_s},
    {"fall_share", &ToleranceScheduleSummary::fall_share}};
constexpr std::pair<const char*, std::int64_t ToleranceScheduleSummary::*> kScheduleCounts[] = {
    {"fall_steps", &ToleranceScheduleSummary::fall_steps},
    {"fall_unconverged_steps", &ToleranceScheduleSummary::fall_unconverged_steps},
    {"tighten_steps", &ToleranceScheduleSummary::tighten_steps}};

}  // namespace

nlohmann::json RunSummary::to_json() const {
  nlohmann::json m = {{"steps", mechanics.steps},
                      {"mean_iterations", mechanics.mean_iterations},
                      {"max_iterations", mechanics.max_iterations},
                      {"unconverged_steps", mechanics.unconverged_steps},
                      {"max_penetration_m", mechanics.max_penetration_m},
                      {"stalled_steps", mechanics.stalled_steps},
                      {"correction_sweeps", mechanics.correction_sweeps},
                      {"max_step_travel_m", mechanics.max_step_travel_m},
                      {"max_siconos_residual", mechanics.max_siconos_residual},
                      {"siconos_unconverged_steps", mechanics.siconos_unconverged_steps}};
  if (const auto& ts = mechanics.tolerance_schedule) {
    nlohmann::json& block = m["tolerance_schedule"];
    for (const auto& [key, member] : kScheduleNumbers) block[key] = (*ts).*member;
    for (const auto& [key, member] : kScheduleCounts) block[key] = (*ts).*member;
    block["tightened"] = ts->tightened;
    block["tightened_step"] = ts->tightened ? nlohmann::json(ts->tightened_step) : nlohmann::json();
    block["tightened_time_s"] = ts->tightened ? nlohmann::json(ts->tightened_time_s) : nlohmann::json();
  }
  nlohmann::json t = {{"integrator", thermal.integrator},
                      {"steps", thermal.steps},
                      {"rhs_evals", thermal.rhs_evals},
                      {"jacobian_evals", thermal.jacobian_evals},
                      {"linear_setups", thermal.linear_setups},
                      {"error_test_failures", thermal.error_test_failures},
                      {"convergence_failures", thermal.convergence_failures},
                      {"reinitializations", thermal.reinitializations}};
  if (!thermal.linear_solver.empty()) t["linear_solver"] = thermal.linear_solver;
  if (!thermal.linear_solver_reason.empty())
    t["linear_solver_reason"] = thermal.linear_solver_reason;
  t["wall_time_s"] = thermal.wall_time_s;
  if (!thermal.coupling.empty()) t["coupling"] = thermal.coupling;
  nlohmann::json e = {{"initial_J", energy.initial_J},
                      {"final_J", energy.final_J},
                      {"boundary_heat_J", energy.boundary_heat_J},
                      {"balance_error_rel", energy.balance_error_rel}};
  if (energy.mechanical) {
    const auto& a = *energy.mechanical;
    nlohmann::json me = {{"energy_change_J", a.energy_change_J},
                         {"contact_dissipation_J", a.contact_dissipation_J},
                         {"numerical_dissipation_J", a.numerical_dissipation_J},
                         {"balance_error_rel", a.balance_error_rel},
                         {"correction_potential_J", a.correction_potential_J}};
    if (a.heat) {
      me["heat_generated_J"] = a.heat_generated_J;
      me["heat_received_J"] = a.heat_received_J;
      me["heat_error_rel"] = a.heat_error_rel;
    }
    e["mechanical"] = std::move(me);
  }
  nlohmann::json j = {{"status", status},
                      {"wall_time_s", wall_time_s},
                      {"simulated_time_s", simulated_time_s},
                      {"particles", particles},
                      {"mechanics", std::move(m)},
                      {"thermal", std::move(t)},
                      {"energy", std::move(e)}};
  if (settle) {
    j["settle"] = {{"at_rest", settle->at_rest},
                   {"time_s", settle->time_s},
                   {"steps", settle->steps},
                   {"max_speed_m_s", settle->max_speed_m_s},
                   {"ended_by", settle->ended_by},
                   {"rattlers", settle->rattlers}};
    if (settle->bed_height_m) j["settle"]["bed_height_m"] = *settle->bed_height_m;
    if (settle->porosity) j["settle"]["porosity"] = *settle->porosity;
  }
  if (thermo_mechanics) {
    j["thermo_mechanics"] = {{"couplings", thermo_mechanics->couplings},
                             {"steps", thermo_mechanics->steps},
                             {"not_at_rest", thermo_mechanics->not_at_rest},
                             {"largest_wall_force_N", thermo_mechanics->largest_wall_force_N},
                             {"last_wall_force_N", thermo_mechanics->last_wall_force_N},
                             {"last_wall_point_m", thermo_mechanics->last_wall_point_m}};
  }
  if (wall_time_parts) {
    j["wall_time_parts"] = {{"mechanics_s", wall_time_parts->mechanics_s},
                            {"thermal_s", wall_time_parts->thermal_s},
                            {"output_s", wall_time_parts->output_s},
                            {"other_s", wall_time_parts->other_s},
                            {"detection_s", wall_time_parts->detection_s},
                            {"contact_solve_s", wall_time_parts->contact_solve_s},
                            {"correction_s", wall_time_parts->correction_s}};
  }
  if (openmp) {
    j["openmp"] = {{"threads", openmp->threads}, {"wait_policy", openmp->wait_policy},
                   {"spin_count", openmp->spin_count}};
  }
  if (mpi) j["mpi"] = {{"processes", mpi->processes}, {"ghosts", mpi->ghosts}};
  for (const auto& i : imports)
    j["imports"].push_back({{"file", i.file},
                            {"particles", i.particles},
                            {"largest_overlap_rel", i.largest_overlap_rel},
                            {"overlap_tolerance", i.overlap_tolerance}});
  if (!message.empty()) j["message"] = message;
  return j;
}

RunSummary RunSummary::from_json(const nlohmann::json& j) {
  RunSummary s;
  s.status = text(j, "status", s.status);
  s.message = text(j, "message", s.message);
  s.wall_time_s = number(j, "wall_time_s", s.wall_time_s);
  s.simulated_time_s = number(j, "simulated_time_s", s.simulated_time_s);
  s.particles = integer(j, "particles", s.particles);

  const nlohmann::json& m = section(j, "mechanics");
  s.mechanics.steps = integer(m, "steps", 0);
  s.mechanics.mean_iterations = number(m, "mean_iterations", 0.0);
  s.mechanics.max_iterations = integer(m, "max_iterations", 0);
  s.mechanics.unconverged_steps = integer(m, "unconverged_steps", 0);
  s.mechanics.max_penetration_m = number(m, "max_penetration_m", 0.0);
  s.mechanics.stalled_steps = integer(m, "stalled_steps", 0);
  s.mechanics.correction_sweeps = integer(m, "correction_sweeps", 0);
  s.mechanics.max_step_travel_m = number(m, "max_step_travel_m", 0.0);
  s.mechanics.max_siconos_residual = number(m, "max_siconos_residual", 0.0);
  s.mechanics.siconos_unconverged_steps = integer(m, "siconos_unconverged_steps", 0);
  if (m.contains("tolerance_schedule")) {
    const nlohmann::json& block = m.at("tolerance_schedule");
    ToleranceScheduleSummary ts;
    for (const auto& [key, member] : kScheduleNumbers) ts.*member = number(block, key, 0.0);
    for (const auto& [key, member] : kScheduleCounts) ts.*member = integer(block, key, 0);
    ts.tightened = block.contains("tightened") && block.at("tightened").get<bool>();
    if (ts.tightened) {  // null (not tightened) stays 0
      ts.tightened_step = integer(block, "tightened_step", 0);
      ts.tightened_time_s = number(block, "tightened_time_s", 0.0);
    }
    s.mechanics.tolerance_schedule = ts;
  }

  if (j.contains("settle")) {
    const nlohmann::json& st = j.at("settle");
    SettleSummary settle;
    settle.at_rest = st.contains("at_rest") && st.at("at_rest").get<bool>();
    settle.time_s = number(st, "time_s", 0.0);
    settle.steps = integer(st, "steps", 0);
    settle.max_speed_m_s = number(st, "max_speed_m_s", 0.0);
    if (st.contains("ended_by")) settle.ended_by = st.at("ended_by").get<std::string>();
    settle.rattlers = integer(st, "rattlers", 0);
    if (st.contains("bed_height_m")) settle.bed_height_m = st.at("bed_height_m").get<double>();
    if (st.contains("porosity")) settle.porosity = st.at("porosity").get<double>();
    s.settle = settle;
  }

  if (j.contains("thermo_mechanics")) {
    const nlohmann::json& c = j.at("thermo_mechanics");
    ThermoMechanicsSummary tm;
    tm.couplings = integer(c, "couplings", 0);
    tm.steps = integer(c, "steps", 0);
    tm.not_at_rest = integer(c, "not_at_rest", 0);
    auto list = [&](const char* key) {
      return c.contains(key) ? c.at(key).get<std::vector<double>>() : std::vector<double>{};
    };
    tm.largest_wall_force_N = list("largest_wall_force_N");
    tm.last_wall_force_N = list("last_wall_force_N");
    tm.last_wall_point_m = list("last_wall_point_m");
    s.thermo_mechanics = tm;
  }

  if (j.contains("wall_time_parts")) {
    const nlohmann::json& w = j.at("wall_time_parts");
    s.wall_time_parts = WallTimeParts{number(w, "mechanics_s", 0.0), number(w, "thermal_s", 0.0),
                                      number(w, "output_s", 0.0), number(w, "other_s", 0.0),
                                      number(w, "detection_s", 0.0),
                                      number(w, "contact_solve_s", 0.0),
                                      number(w, "correction_s", 0.0)};
  }

  if (j.contains("openmp")) {
    const nlohmann::json& o = j.at("openmp");
    s.openmp = OpenMpSummary{integer(o, "threads", 1), text(o, "wait_policy", ""),
                             text(o, "spin_count", "unset")};
  }

  if (j.contains("mpi")) {
    const nlohmann::json& m = j.at("mpi");
    s.mpi = MpiSummary{integer(m, "processes", 1), integer(m, "ghosts", 0)};
  }

  if (j.contains("imports"))
    for (const auto& i : j.at("imports"))
      s.imports.push_back({text(i, "file", ""), integer(i, "particles", 0),
                           number(i, "largest_overlap_rel", 0.0), number(i, "overlap_tolerance", 0.0)});

  const nlohmann::json& t = section(j, "thermal");
  s.thermal.integrator = text(t, "integrator", s.thermal.integrator);
  s.thermal.linear_solver = text(t, "linear_solver", "");
  s.thermal.linear_solver_reason = text(t, "linear_solver_reason", "");
  s.thermal.steps = integer(t, "steps", 0);
  s.thermal.rhs_evals = integer(t, "rhs_evals", 0);
  s.thermal.jacobian_evals = integer(t, "jacobian_evals", 0);
  s.thermal.linear_setups = integer(t, "linear_setups", 0);
  s.thermal.error_test_failures = integer(t, "error_test_failures", 0);
  s.thermal.convergence_failures = integer(t, "convergence_failures", 0);
  s.thermal.reinitializations = integer(t, "reinitializations", 0);
  s.thermal.wall_time_s = number(t, "wall_time_s", 0.0);
  s.thermal.coupling = text(t, "coupling", "");

  const nlohmann::json& e = section(j, "energy");
  s.energy.initial_J = number(e, "initial_J", 0.0);
  s.energy.final_J = number(e, "final_J", 0.0);
  s.energy.boundary_heat_J = number(e, "boundary_heat_J", 0.0);
  s.energy.balance_error_rel = number(e, "balance_error_rel", 0.0);
  if (e.contains("mechanical")) {
    const nlohmann::json& me = e.at("mechanical");
    MechanicalEnergySummary a;
    a.energy_change_J = number(me, "energy_change_J", 0.0);
    a.contact_dissipation_J = number(me, "contact_dissipation_J", 0.0);
    a.numerical_dissipation_J = number(me, "numerical_dissipation_J", 0.0);
    a.balance_error_rel = number(me, "balance_error_rel", 0.0);
    a.correction_potential_J = number(me, "correction_potential_J", 0.0);
    a.heat = me.contains("heat_generated_J");
    a.heat_generated_J = number(me, "heat_generated_J", 0.0);
    a.heat_received_J = number(me, "heat_received_J", 0.0);
    a.heat_error_rel = number(me, "heat_error_rel", 0.0);
    s.energy.mechanical = a;
  }
  return s;
}

void RunSummary::write(const std::string& path) const {
  const std::string text = to_json().dump(2) + "\n";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError("cannot write run summary '" + path + "': cannot create the file");
  out << text;
  out.close();
  if (!out) throw OutputError("cannot write run summary '" + path + "': write failed");
}

MechanicalEnergySummary MechanicalEnergySummary::with_errors(bool heat_on) const {
  MechanicalEnergySummary a = *this;
  const double scale =
      std::max(std::abs(energy_change_J), std::abs(contact_dissipation_J) + std::abs(numerical_dissipation_J));
  a.balance_error_rel =
      scale == 0.0 ? 0.0
                   : std::abs(energy_change_J + contact_dissipation_J + numerical_dissipation_J) / scale;
  a.heat = heat_on;
  a.heat_error_rel = 0.0;
  if (!heat_on) return a;
  // The run's bookkeeping: what it handed over against what the mechanics dissipated.
  if (contact_dissipation_J == 0.0)
    a.heat_error_rel = heat_generated_J == 0.0 ? 0.0 : 1.0;  // heat out of nothing: all wrong
  else
    a.heat_error_rel =
        std::abs(heat_generated_J - contact_dissipation_J) / std::abs(contact_dissipation_J);
  // The integrator's: what it integrated of the particles' share against the exact integral.
  const double received_scale = std::max(std::abs(heat_share_J), std::abs(heat_received_J));
  if (received_scale > 0.0)
    a.heat_error_rel = std::max(a.heat_error_rel,
                                std::abs(heat_received_J - heat_share_J) / received_scale);
  return a;
}

double RunSummary::balance_error_rel(double initial_J, double final_J, double boundary_heat_J) {
  const double scale = std::max(std::abs(initial_J), std::abs(boundary_heat_J));
  if (scale == 0.0) return 0.0;  // nothing to compare with (as specified)
  return std::abs(final_J - initial_J - boundary_heat_J) / scale;
}

}  // namespace tmdem::coupling
