// Validation rules of contract section 2 on the run's settings: dimension and gravity, seed,
// integrator, solver and conductance choices, tolerances and their schedule, steps and
// intervals, theta, iteration limits, mechanics off with Hertz conductance and convection.
// Loading throws SceneError and the message names the key path (and the allowed values or range).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "tests/coupling/SceneTestUtil.h"
#include "tests/coupling/scene/SceneRulesText.h"

namespace tmdem::coupling::test {
namespace {

using namespace scene_rules;

TEST(SceneRules, DimensionTwoOrThree) {
  expect_scene_error(kBaseScene, {"simulation.dimension=4"},
                     {"simulation.dimension", "must be 2 or 3", "got 4"});
}

TEST(SceneRules, GravityZInTwoDimensions) {
  expect_scene_error(kBaseScene, {"simulation.dimension=2", "simulation.gravity=[0, -9.81, 1]"},
                     {"simulation.gravity", "z component must be 0"});
}

TEST(SceneRules, SeedNonNegative) {
  expect_scene_error(kBaseScene, {"simulation.seed=-1"}, {"simulation.seed", ">= 0"});
}

TEST(SceneRules, IntegratorChoice) {
  expect_scene_error(kBaseScene, {"thermal.integrator=rk4"},
                     {"thermal.integrator", "must be one of \"cvode\", \"ida\", \"explicit\"",
                      "got \"rk4\""});
}

TEST(SceneRules, LinearSolverChoice) {
  expect_scene_error(kBaseScene, {"thermal.linear_solver=gmres"},
                     {"thermal.linear_solver", "\"klu\", \"pcg\""});
}

TEST(SceneRules, ConductanceChoice) {
  expect_scene_error(kBaseScene, {"thermal.conductance=linear"},
                     {"thermal.conductance", "\"hertz\", \"constant\""});
}

TEST(SceneRules, MechanicsChoice) {
  expect_scene_error(kBaseScene, {"effects.mechanics=on"},
                     {"effects.mechanics", "\"dynamic\", \"settle\", \"coupled\", \"off\""});
}

TEST(SceneRules, TolerancesPositive) {
  for (const char* key :
       {"thermal.relative_tolerance", "thermal.absolute_tolerance", "mechanics.tolerance"}) {
    SCOPED_TRACE(key);
    expect_scene_error(kBaseScene, {std::string(key) + "=0"}, {key, "must be > 0"});
    expect_scene_error(kBaseScene, {std::string(key) + "=-1e-6"}, {key, "must be > 0"});
  }
}

// The tolerance schedule (mechanics::ToleranceSchedule): on by default, fall_tolerance 0 turns
// it off, fall_speed absent is automatic (0 in the parameters), each key range-checked.
TEST(SceneRules, ToleranceSchedule) {
  expect_scene_error(kBaseScene, {"mechanics.fall_speed=0"}, {"mechanics.fall_speed", "must be > 0"});
  expect_scene_error(kBaseScene, {"mechanics.fall_speed=-1"}, {"mechanics.fall_speed", "must be > 0"});
  expect_scene_error(kBaseScene, {"mechanics.fall_tolerance=-1"}, {"mechanics.fall_tolerance", "must be >= 0"});
  for (const char* key : {"mechanics.fall_tolerance", "mechanics.fall_speed"}) {
    SCOPED_TRACE(key);
    expect_scene_error(kBaseScene, {std::string(key) + "=nan"}, {key});
    expect_scene_error(kBaseScene, {std::string(key) + "=\"fast\""}, {key});
  }
  expect_scene_error(kBaseScene, {"mechanics.tighten_steps=0"}, {"mechanics.tighten_steps", ">= 1"});
  expect_scene_error(kBaseScene, {"mechanics.tighten_steps=2.5"}, {"mechanics.tighten_steps"});
  EXPECT_EQ(make_nscd_parameters(load_scene_text(kBaseScene, "t", {"mechanics.tighten_steps=4"})).tighten_steps, 4);
  const Scene defaults = load_scene_text(kBaseScene, "t");
  EXPECT_EQ(make_nscd_parameters(defaults).fall_tolerance, mechanics::NscdParameters{}.fall_tolerance);
  EXPECT_GT(make_nscd_parameters(defaults).fall_tolerance, make_nscd_parameters(defaults).tolerance);
  EXPECT_EQ(make_nscd_parameters(defaults).fall_speed, 0.0);  // automatic
  // compaction_speed: absent automatic (no value), 0 off, a speed as given, negative refused.
  EXPECT_FALSE(make_nscd_parameters(defaults).compaction_speed.has_value());
  EXPECT_EQ(make_nscd_parameters(load_scene_text(kBaseScene, "t", {"mechanics.compaction_speed=0"}))
                .compaction_speed, 0.0);
  EXPECT_EQ(make_nscd_parameters(load_scene_text(kBaseScene, "t", {"mechanics.compaction_speed=2e-3"}))
                .compaction_speed, 2e-3);
  expect_scene_error(kBaseScene, {"mechanics.compaction_speed=-1e-4"},
                     {"mechanics.compaction_speed", ">= 0"});
  expect_scene_error(kBaseScene, {"mechanics.compaction_speed=nan"}, {"mechanics.compaction_speed"});
  // retry_parts: 8 by default, an integer in [1, 64], the key named when out of it.
  EXPECT_EQ(make_nscd_parameters(defaults).retry_parts, 8);
  EXPECT_EQ(make_nscd_parameters(load_scene_text(kBaseScene, "t", {"mechanics.retry_parts=1"})).retry_parts, 1);
  expect_scene_error(kBaseScene, {"mechanics.retry_parts=0"}, {"mechanics.retry_parts"});
  expect_scene_error(kBaseScene, {"mechanics.retry_parts=65"}, {"mechanics.retry_parts"});
  expect_scene_error(kBaseScene, {"mechanics.retry_parts=2.5"}, {"mechanics.retry_parts"});
  const Scene off = load_scene_text(kBaseScene, "t", {"mechanics.fall_tolerance=0"});
  EXPECT_EQ(make_nscd_parameters(off).fall_tolerance, 0.0);
  const Scene on = load_scene_text(kBaseScene, "t", {"mechanics.fall_tolerance=1e-3", "mechanics.fall_speed=0.1"});
  EXPECT_EQ(make_nscd_parameters(on).fall_tolerance, 1e-3);
  EXPECT_EQ(make_nscd_parameters(on).fall_speed, 0.1);
  // Ignored, as every [mechanics] key, when mechanics is off.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                  {"effects.mechanics=\"off\"", "thermal.conductance=\"constant\"",
                                   "mechanics.fall_speed=-1"}));
}

TEST(SceneRules, ExplicitStepNonNegative) {
  expect_scene_error(kBaseScene, {"thermal.explicit_step=-1e-3"},
                     {"thermal.explicit_step", "must be >= 0"});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"thermal.explicit_step=0"}));
}

TEST(SceneRules, OutputIntervalPositive) {
  expect_scene_error(kBaseScene, {"output.interval=0"}, {"output.interval", "must be > 0"});
}

TEST(SceneRules, CheckpointIntervalNonNegative) {
  expect_scene_error(kBaseScene, {"output.checkpoint_interval=-1"},
                     {"output.checkpoint_interval", "must be >= 0"});
}

TEST(SceneRules, TimeStepPositive) {
  expect_scene_error(kBaseScene, {"mechanics.time_step=0"}, {"mechanics.time_step", "must be > 0"});
}

TEST(SceneRules, ThetaInZeroOne) {
  expect_scene_error(kBaseScene, {"mechanics.theta=0"}, {"mechanics.theta", "must be in (0, 1]"});
  expect_scene_error(kBaseScene, {"mechanics.theta=1.5"}, {"mechanics.theta", "(0, 1]"});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"mechanics.theta=1"}));
}

TEST(SceneRules, SolverByNameListsTheValidNames) {
  expect_scene_error(kBaseScene, {"mechanics.solver=jacobi_typo"},
                     {"mechanics.solver", "\"nlgs\"", "\"jacobi_typo\""});
  EXPECT_EQ(load_scene_text(kBaseScene, "t", {"mechanics.solver=nlgs"}).mechanics.solver, "nlgs");
  // The default is nncg_ipm: nncg (fastest to rest and most steps converged on every example,
  // docs/mechanics.md), with the interior point on the steps it leaves unconverged.
  EXPECT_EQ(load_scene_text(kBaseScene, "t").mechanics.solver, "nncg_ipm");
}

TEST(SceneRules, MaxIterationsAtLeastOne) {
  expect_scene_error(kBaseScene, {"mechanics.max_iterations=0"},
                     {"mechanics.max_iterations", ">= 1"});
}

// The Gauss-Seidel active-set period (mechanics::NscdParameters::full_sweep_every): an integer
// >= 1, 1 (every sweep over every candidate) unless set.
TEST(SceneRules, FullSweepEveryAtLeastOne) {
  expect_scene_error(kBaseScene, {"mechanics.full_sweep_every=0"},
                     {"mechanics.full_sweep_every", ">= 1"});
  expect_scene_error(kBaseScene, {"mechanics.full_sweep_every=2.5"}, {"mechanics.full_sweep_every"});
  EXPECT_EQ(load_scene_text(kBaseScene, "t").mechanics.full_sweep_every, 1);
  const Scene scene = load_scene_text(kBaseScene, "t", {"mechanics.full_sweep_every=8"});
  EXPECT_EQ(scene.mechanics.full_sweep_every, 8);
  EXPECT_EQ(make_nscd_parameters(scene).full_sweep_every, 8);  // what the solvers are given
}

// The sweeps between checks of Siconos' residual before nncg's sweep test is met
// (mechanics::NscdParameters::residual_check_every): an integer >= 0 (0: never), handed to the
// solver's settings.
TEST(SceneRules, ResidualCheckEveryAtLeastZero) {
  expect_scene_error(kBaseScene, {"mechanics.residual_check_every=-1"},
                     {"mechanics.residual_check_every", ">= 0"});
  expect_scene_error(kBaseScene, {"mechanics.residual_check_every=2.5"}, {"mechanics.residual_check_every"});
  EXPECT_EQ(load_scene_text(kBaseScene, "t").mechanics.residual_check_every,
            mechanics::NscdParameters{}.residual_check_every);
  const Scene scene = load_scene_text(kBaseScene, "t", {"mechanics.residual_check_every=0"});
  EXPECT_EQ(make_nscd_parameters(scene).residual_check_every, 0);
  EXPECT_EQ(make_nscd_parameters(load_scene_text(kBaseScene, "t", {"mechanics.residual_check_every=50"}))
                .residual_check_every,
            50);
}

TEST(SceneRules, MechanicsOffWithHertzConductance) {
  expect_scene_error(kBaseScene, {"effects.mechanics=off", "thermal.conductance=hertz"},
                     {"thermal.conductance", "\"hertz\"", "effects.mechanics = \"off\""});
  // Without an explicit conductance the default "hertz" is meant: name effects.mechanics.
  expect_scene_error(kBaseScene, {"effects.mechanics=off"},
                     {"effects.mechanics", "thermal.conductance = \"constant\""});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                  {"effects.mechanics=off", "thermal.conductance=constant"}));
}

TEST(SceneRules, ConvectionValuesWhenOn) {
  const Scene scene = load_scene_text(kBaseScene + "\n[effects]\nconvection = true\n"
                                                   "[convection]\ncoefficient = 25.0\n"
                                                   "fluid_temperature = 310.0\n",
                                      "t");
  EXPECT_TRUE(scene.effects.on("convection"));
  EXPECT_DOUBLE_EQ(scene.heat_modes.find("convection", "coefficient").value(), 25.0);
  EXPECT_DOUBLE_EQ(scene.heat_modes.find("convection", "fluid_temperature").value(), 310.0);
}

}  // namespace
}  // namespace tmdem::coupling::test
