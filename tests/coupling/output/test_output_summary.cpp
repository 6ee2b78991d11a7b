// RunSummary: contract section 4.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "coupling/output/RunSummary.h"

namespace {

namespace fs = std::filesystem;
using tmdem::coupling::OutputError;
using tmdem::coupling::RunSummary;

RunSummary sample_summary() {
  RunSummary s;
  s.status = "ok";
  s.wall_time_s = 1.25;
  s.simulated_time_s = 100.0;
  s.particles = 256;
  s.mechanics = {1200, 35.5, 812, 2, 3.5e-7};
  s.thermal.integrator = "ida";
  s.thermal.steps = 410;
  s.thermal.rhs_evals = 523;
  s.thermal.jacobian_evals = 12;
  s.thermal.linear_setups = 40;
  s.thermal.error_test_failures = 3;
  s.thermal.convergence_failures = 1;
  s.thermal.reinitializations = 7;
  s.energy = {1000.0, 1010.0, 10.5, RunSummary::balance_error_rel(1000.0, 1010.0, 10.5),
              std::nullopt};
  return s;
}

TEST(RunSummary, JsonHasEveryContractKey) {
  const nlohmann::json j = sample_summary().to_json();
  for (const char* key : {"status", "wall_time_s", "simulated_time_s", "particles", "mechanics",
                          "settle", "thermal", "energy"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_TRUE(j["status"].is_string());
  EXPECT_TRUE(j["particles"].is_number_integer());
  for (const char* key :
       {"steps", "mean_iterations", "max_iterations", "unconverged_steps", "max_penetration_m"}) {
    EXPECT_TRUE(j["mechanics"].contains(key) && j["mechanics"][key].is_number()) << key;
  }
  EXPECT_TRUE(j["thermal"]["integrator"].is_string());
  for (const char* key : {"steps", "rhs_evals", "jacobian_evals", "linear_setups",
                          "error_test_failures", "convergence_failures", "reinitializations"}) {
    EXPECT_TRUE(j["thermal"].contains(key) && j["thermal"][key].is_number_integer()) << key;
  }
  for (const char* key : {"initial_J", "final_J", "boundary_heat_J", "balance_error_rel"}) {
    EXPECT_TRUE(j["energy"].contains(key) && j["energy"][key].is_number()) << key;
  }
  // Extras only when set.
  EXPECT_FALSE(j.contains("message"));
  EXPECT_FALSE(j["thermal"].contains("linear_solver"));
  EXPECT_FALSE(j["thermal"].contains("linear_solver_reason"));
  // The contract's settle block, for a run without a settle phase: not judged (null), no settle
  // time or steps.
  for (const char* key : {"at_rest", "time_s", "steps", "max_speed_m_s"}) EXPECT_TRUE(j["settle"].contains(key)) << key;
  EXPECT_TRUE(j["settle"]["at_rest"].is_null());
  EXPECT_TRUE(j["settle"]["max_speed_m_s"].is_null());
  EXPECT_EQ(j["settle"]["time_s"], 0.0);
  EXPECT_EQ(j["settle"]["steps"], 0);
  EXPECT_EQ(j["settle"]["ended_by"], "none");
  EXPECT_EQ(j.size(), 8u);
  // The contract's 5 mechanics keys plus the extras stalled_steps, correction_sweeps,
  // halved_steps, landing_halved_steps, retried_steps, discarded_sweeps, piston_corrections,
  // max_step_travel_m, max_siconos_residual, siconos_unconverged_steps,
  // max_natural_map_residual, unconverged_time_steps, kept_parts_steps and relisted_steps.
  EXPECT_EQ(j["mechanics"].size(), 19u);
  EXPECT_TRUE(j["mechanics"]["kept_parts_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["relisted_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["retried_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["discarded_sweeps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["piston_corrections"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["halved_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["landing_halved_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["max_siconos_residual"].is_number());
  EXPECT_TRUE(j["mechanics"]["siconos_unconverged_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["max_natural_map_residual"].is_number());
  EXPECT_TRUE(j["mechanics"]["stalled_steps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["correction_sweeps"].is_number_integer());
  EXPECT_TRUE(j["mechanics"]["max_step_travel_m"].is_number());
  // The contract's 8 thermal keys plus the extra wall_time_s (time in the thermal side alone).
  EXPECT_EQ(j["thermal"].size(), 9u);
  EXPECT_TRUE(j["thermal"]["wall_time_s"].is_number());
  EXPECT_FALSE(j["thermal"].contains("coupling"));
  EXPECT_EQ(j["energy"].size(), 4u);
}

TEST(RunSummary, FileRoundTrip) {
  const fs::path path =
      fs::temp_directory_path() / ("tmdem-output-summary-" + std::to_string(getpid()) + ".json");
  RunSummary s = sample_summary();
  s.status = "failed";
  s.message = "CVODE failed at t = 3.2 s";
  s.thermal.linear_solver = "pcg";
  s.write(path.string());
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  fs::remove(path);
  EXPECT_EQ(j, s.to_json());
  EXPECT_EQ(j["message"], "CVODE failed at t = 3.2 s");
  EXPECT_EQ(j["thermal"]["linear_solver"], "pcg");
  const RunSummary r = RunSummary::from_json(j);
  EXPECT_EQ(r.to_json(), s.to_json());
  EXPECT_EQ(r.mechanics.max_iterations, 812);
  EXPECT_EQ(r.thermal.reinitializations, 7);
  EXPECT_DOUBLE_EQ(r.energy.boundary_heat_J, 10.5);
}

// The resolved linear solver and why ("auto" or explicit): extras, written only when set.
TEST(RunSummary, LinearSolverReasonRoundTrips) {
  RunSummary s = sample_summary();
  s.thermal.linear_solver = "pcg";
  s.thermal.linear_solver_reason = "auto: 25000 particles >= 5000 in 3D, symmetric Jacobian";
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_EQ(j["thermal"]["linear_solver"], "pcg");
  EXPECT_EQ(j["thermal"]["linear_solver_reason"],
            "auto: 25000 particles >= 5000 in 3D, symmetric Jacobian");
  EXPECT_EQ(j["thermal"].size(), 11u);  // 9 (see above) + linear_solver + linear_solver_reason
  const RunSummary r = RunSummary::from_json(j);
  EXPECT_EQ(r.thermal.linear_solver, "pcg");
  EXPECT_EQ(r.thermal.linear_solver_reason, s.thermal.linear_solver_reason);
  EXPECT_EQ(r.to_json(), s.to_json());
  // Summaries written before the reason existed read back without one, and write none.
  nlohmann::json old = j;
  old["thermal"].erase("linear_solver_reason");
  EXPECT_EQ(RunSummary::from_json(old).thermal.linear_solver_reason, "");
  EXPECT_FALSE(RunSummary::from_json(old).to_json()["thermal"].contains("linear_solver_reason"));
}

// The default solver's later stages: a block written when set (a solver that has them), read back.
TEST(RunSummary, FallbackBlockRoundTrips) {
  RunSummary s = sample_summary();
  EXPECT_FALSE(s.to_json()["mechanics"].contains("fallback"));
  s.mechanics.fallback = tmdem::coupling::FallbackSummary{12, 5, 3, 1, 2, 4321, 2.5, 98765, 7.25};
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  const auto& f = j["mechanics"]["fallback"];
  EXPECT_EQ(f.size(), 9u);
  EXPECT_EQ(f["first_sweeps"], 98765);
  EXPECT_DOUBLE_EQ(f["first_wall_time_s"].get<double>(), 7.25);
  EXPECT_EQ(f["within_when_handed_on"], 2);
  EXPECT_EQ(f["solves"], 12);
  EXPECT_EQ(f["converged_by_second"], 5);
  EXPECT_EQ(f["converged_by_first_again"], 3);
  EXPECT_EQ(f["converged_by_sweeps"], 1);
  EXPECT_EQ(f["sweeps"], 4321);
  EXPECT_DOUBLE_EQ(f["wall_time_s"].get<double>(), 2.5);
  EXPECT_EQ(j["mechanics"].size(), 20u);  // the 19 above and the block
  const RunSummary r = RunSummary::from_json(j);
  ASSERT_TRUE(r.mechanics.fallback.has_value());
  EXPECT_EQ(r.mechanics.fallback->converged_by_first_again, 3);
  EXPECT_EQ(r.to_json(), s.to_json());
}

TEST(RunSummary, SettleBlockAndStalledStepsRoundTrip) {
  RunSummary s = sample_summary();
  s.mechanics.stalled_steps = 3;
  s.settle = tmdem::coupling::SettleSummary{false, 5.0, 5000, 1.15e-3, "settle_time", 0, std::nullopt, std::nullopt};
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  ASSERT_TRUE(j.contains("settle"));
  EXPECT_EQ(j["settle"].size(), 6u);
  EXPECT_EQ(j["settle"]["ended_by"].get<std::string>(), "settle_time");
  EXPECT_EQ(j["settle"]["rattlers"].get<std::int64_t>(), 0);
  EXPECT_TRUE(j["settle"]["at_rest"].is_boolean());
  EXPECT_FALSE(j["settle"]["at_rest"].get<bool>());
  EXPECT_EQ(j["settle"]["time_s"].get<double>(), 5.0);
  EXPECT_EQ(j["settle"]["steps"].get<std::int64_t>(), 5000);
  EXPECT_EQ(j["settle"]["max_speed_m_s"].get<double>(), 1.15e-3);
  EXPECT_EQ(j["mechanics"]["stalled_steps"].get<std::int64_t>(), 3);
  const RunSummary r = RunSummary::from_json(j);
  ASSERT_TRUE(r.settle.has_value());
  EXPECT_EQ(r.settle->steps, 5000);
  EXPECT_EQ(r.mechanics.stalled_steps, 3);
  EXPECT_EQ(r.to_json(), s.to_json());
}

// The contract lists the "settle" block for every run. Without a settle phase: a packing held
// as given (mechanics "off") is at rest with speed 0; otherwise at_rest and the speed are null
// (not judged). Both read back as "no settle phase" and write the same block again.
TEST(RunSummary, SettleBlockWithoutSettlePhaseRoundTrips) {
  for (const bool held : {true, false}) {
    RunSummary s = sample_summary();
    s.packing_held = held;
    const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
    ASSERT_TRUE(j.contains("settle"));
    EXPECT_EQ(j["settle"]["ended_by"], "none");
    EXPECT_EQ(j["settle"]["steps"], 0);
    EXPECT_EQ(j["settle"]["time_s"], 0.0);
    if (held) {
      EXPECT_EQ(j["settle"]["at_rest"], true);
      EXPECT_EQ(j["settle"]["max_speed_m_s"], 0.0);
    } else {
      EXPECT_TRUE(j["settle"]["at_rest"].is_null());
      EXPECT_TRUE(j["settle"]["max_speed_m_s"].is_null());
    }
    const RunSummary r = RunSummary::from_json(j);
    EXPECT_FALSE(r.settle.has_value());
    EXPECT_EQ(r.packing_held, held);
    EXPECT_EQ(r.to_json(), s.to_json());
  }
}

// The tolerance schedule's block (mechanics.tolerance_schedule): only for scenes with one,
// null step and time while the tolerance has not tightened.
TEST(RunSummary, ToleranceScheduleBlockRoundTrips) {
  RunSummary s = sample_summary();
  EXPECT_FALSE(s.to_json()["mechanics"].contains("tolerance_schedule"));
  tmdem::coupling::ToleranceScheduleSummary ts;
  ts.tolerance = 1e-5;
  ts.fall_tolerance = 1e-4;
  ts.fall_speed_m_s = 0.05;
  ts.fall_share = 0.01;
  ts.compaction_speed_m_s = 2.4e-3;
  ts.fall_steps = 200;
  ts.fall_unconverged_steps = 1;
  ts.collapse_steps = 3;
  s.mechanics.tolerance_schedule = ts;
  nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  const auto& block = j["mechanics"]["tolerance_schedule"];
  EXPECT_EQ(block.size(), 12u);
  EXPECT_EQ(block["collapse_steps"].get<std::int64_t>(), 3);
  EXPECT_EQ(block["compaction_speed_m_s"].get<double>(), 2.4e-3);
  EXPECT_FALSE(block["tightened"].get<bool>());
  EXPECT_TRUE(block["tightened_step"].is_null());
  EXPECT_TRUE(block["tightened_time_s"].is_null());
  EXPECT_EQ(RunSummary::from_json(j).to_json(), s.to_json());

  s.mechanics.tolerance_schedule->tightened = true;
  s.mechanics.tolerance_schedule->tightened_step = 207;
  s.mechanics.tolerance_schedule->tightened_time_s = 0.206;
  s.mechanics.tolerance_schedule->tighten_steps = 4;
  j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_EQ(j["mechanics"]["tolerance_schedule"]["tightened_step"].get<std::int64_t>(), 207);
  EXPECT_EQ(j["mechanics"]["tolerance_schedule"]["tightened_time_s"].get<double>(), 0.206);
  EXPECT_EQ(j["mechanics"]["tolerance_schedule"]["fall_speed_m_s"].get<double>(), 0.05);
  EXPECT_EQ(j["mechanics"]["tolerance_schedule"]["fall_share"].get<double>(), 0.01);
  const RunSummary r = RunSummary::from_json(j);
  ASSERT_TRUE(r.mechanics.tolerance_schedule.has_value());
  EXPECT_EQ(r.mechanics.tolerance_schedule->tightened_step, 207);
  EXPECT_EQ(r.mechanics.tolerance_schedule->fall_unconverged_steps, 1);
  EXPECT_EQ(r.mechanics.tolerance_schedule->tighten_steps, 4);
  EXPECT_EQ(r.to_json(), s.to_json());
}

// The penetration correction's cost (mechanics.correction_sweeps), its potential energy
// (energy.mechanical.correction_potential_J) and the largest travel per step survive the file.
TEST(RunSummary, CorrectionAndTravelRoundTrip) {
  RunSummary s = sample_summary();
  s.mechanics.correction_sweeps = 50655;
  s.mechanics.max_step_travel_m = 7.0e-4;
  s.mechanics.max_siconos_residual = 1.1e-4;
  s.mechanics.siconos_unconverged_steps = 12;
  s.mechanics.max_natural_map_residual = 3.5e-5;
  s.mechanics.unconverged_time_steps = 7;
  tmdem::coupling::MechanicalEnergySummary m;
  m.energy_change_J = -2.0;
  m.contact_dissipation_J = 2.0;
  m.correction_potential_J = 3.25e-8;
  s.energy.mechanical = m.with_errors(false);
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_EQ(j["mechanics"]["correction_sweeps"].get<std::int64_t>(), 50655);
  EXPECT_EQ(j["mechanics"]["max_step_travel_m"].get<double>(), 7.0e-4);
  EXPECT_EQ(j["energy"]["mechanical"]["correction_potential_J"].get<double>(), 3.25e-8);
  // Outside the velocity steps' balance: that one still closes.
  EXPECT_EQ(j["energy"]["mechanical"]["balance_error_rel"].get<double>(), 0.0);
  const RunSummary r = RunSummary::from_json(j);
  EXPECT_EQ(r.mechanics.correction_sweeps, 50655);
  EXPECT_EQ(r.mechanics.max_siconos_residual, 1.1e-4);
  EXPECT_EQ(r.mechanics.siconos_unconverged_steps, 12);
  EXPECT_EQ(j["mechanics"]["max_natural_map_residual"].get<double>(), 3.5e-5);
  EXPECT_EQ(r.mechanics.max_natural_map_residual, 3.5e-5);
  EXPECT_EQ(j["mechanics"]["unconverged_time_steps"].get<std::int64_t>(), 7);
  EXPECT_EQ(r.mechanics.unconverged_time_steps, 7);
  ASSERT_TRUE(r.energy.mechanical.has_value());
  EXPECT_EQ(r.energy.mechanical->correction_potential_J, 3.25e-8);
  EXPECT_EQ(r.to_json(), s.to_json());
}

TEST(RunSummary, WriteToMissingFolderThrowsOutputErrorNamingThePath) {
  const std::string path = "/nonexistent-tmdem-folder/summary.json";
  try {
    sample_summary().write(path);
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(RunSummary, BalanceErrorFormula) {
  // |final - initial - boundary_heat| / max(|initial|, |boundary_heat|)
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(100.0, 110.0, 10.0), 0.0);
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(100.0, 111.0, 10.0), 0.01);
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(100.0, 109.0, 10.0), 0.01);
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(1.0, -48.0, -50.0), 1.0 / 50.0);  // heat left
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(0.0, 0.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(RunSummary::balance_error_rel(-4.0, -4.0, 0.0), 0.0);
}

TEST(RunSummary, NonFiniteNumbersSurviveAsNull) {
  RunSummary s = sample_summary();
  s.energy.balance_error_rel = std::nan("");
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_TRUE(j["energy"]["balance_error_rel"].is_null());
  EXPECT_TRUE(std::isnan(RunSummary::from_json(j).energy.balance_error_rel));
}

}  // namespace

TEST(RunSummary, WallTimePartsAndImportsRoundTrip) {
  RunSummary s = sample_summary();
  EXPECT_FALSE(s.to_json().contains("imports"));  // only for scenes with [[import]]
  s.wall_time_parts = tmdem::coupling::WallTimeParts{0.75, 0.25, 0.125, 0.125, 0.5, 0.125, 0.0625};
  s.imports.push_back({"bed.csv", 80, 9.942771135237893e-05, 0.01});
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_EQ(j["wall_time_parts"]["mechanics_s"].get<double>(), 0.75);
  EXPECT_EQ(j["wall_time_parts"]["other_s"].get<double>(), 0.125);
  ASSERT_EQ(j["imports"].size(), 1u);
  EXPECT_EQ(j["imports"][0]["file"], "bed.csv");
  EXPECT_EQ(j["imports"][0]["largest_overlap_rel"].get<double>(), 9.942771135237893e-05);
  const RunSummary r = RunSummary::from_json(j);
  ASSERT_TRUE(r.wall_time_parts.has_value());
  EXPECT_EQ(r.wall_time_parts->thermal_s, 0.25);
  EXPECT_EQ(r.wall_time_parts->contact_solve_s, 0.125);
  EXPECT_EQ(r.wall_time_parts->correction_s, 0.0625);
  ASSERT_EQ(r.imports.size(), 1u);
  EXPECT_EQ(r.imports[0].particles, 80);
  EXPECT_EQ(r.to_json(), s.to_json());
}

TEST(RunSummary, OpenMpBlockOnlyWhenSetAndRoundTrips) {
  RunSummary s = sample_summary();
  EXPECT_FALSE(s.to_json().contains("openmp"));
  s.openmp = tmdem::coupling::OpenMpSummary{2, "unset", "10000"};
  const nlohmann::json j = nlohmann::json::parse(s.to_json().dump());
  EXPECT_EQ(j["openmp"]["threads"], 2);
  EXPECT_EQ(j["openmp"]["wait_policy"], "unset");
  EXPECT_EQ(j["openmp"]["spin_count"], "10000");
  const RunSummary r = RunSummary::from_json(j);
  ASSERT_TRUE(r.openmp.has_value());
  EXPECT_EQ(r.openmp->threads, 2);
  EXPECT_EQ(r.openmp->wait_policy, "unset");
  EXPECT_EQ(r.openmp->spin_count, "10000");
}
