// One test per validation rule of contract section 2: loading throws SceneError and the message
// names the key path (and the allowed values or range).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

std::string replaced(std::string text, std::string_view from, std::string_view to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(SceneRules, BaseSceneLoads) {
  const Scene scene = load_scene_text(kBaseScene, "test.toml");
  EXPECT_EQ(scene.particles.size(), 2u);
  EXPECT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.walls.size(), 1u);
  EXPECT_EQ(scene.source, "test.toml");
}

TEST(SceneRules, UnknownTopLevelKey) {
  expect_scene_error(kBaseScene + "\nfoo = 1\n", {"foo", "unknown key", "valid keys here:"});
}

TEST(SceneRules, UnknownKeyInSectionSuggestsAndListsValidKeys) {
  expect_scene_error(kBaseScene + "\n[thermal]\nintegratr = \"ida\"\n",
                     {"test.toml:", "thermal.integratr", "did you mean integrator",
                      "integrator, linear_solver, relative_tolerance"});
}

TEST(SceneRules, UnknownKeyInArrayOfTables) {
  expect_scene_error(replaced(kBaseScene, "emissivity = 0.9", "emissivity = 0.9\ncolour = 1"),
                     {"material[1].colour", "unknown key"});
}

TEST(SceneRules, UnknownKeyInInlineTable) {
  expect_scene_error(kBaseScene + "\n[[assign]]\nbox = { min = [0,0,0], max = [1,1,1], "
                                  "maxx = 3 }\ntemperature = 300.0\n",
                     {"assign[0].box.maxx", "unknown key", "min, max"});
}

TEST(SceneRules, WrongTypeNumber) {
  expect_scene_error(replaced(kBaseScene, "duration = 10", "duration = \"ten\""),
                     {"test.toml:4:", "simulation.duration", "expected a number, got a string"});
}

TEST(SceneRules, WrongTypeBoolean) {
  expect_scene_error(kBaseScene, {"effects.conduction=1"},
                     {"effects.conduction", "expected a boolean"});
}

TEST(SceneRules, WrongTypeString) {
  expect_scene_error(kBaseScene, {"thermal.integrator=3"},
                     {"thermal.integrator", "expected a string, got an integer"});
}

TEST(SceneRules, WrongTypeTable) {
  expect_scene_error("thermal = 3\n" + kBaseScene, {"test.toml:1:11: thermal", "expected a table"});
}

TEST(SceneRules, WrongTypeArrayOfTables) {
  expect_scene_error("format = \"tmdem-scene-1\"\nmaterial = 5\n[simulation]\nduration = 1\n",
                     {"material", "expected an array of tables ([[material]])"});
}

TEST(SceneRules, WrongTypeInteger) {
  expect_scene_error(kBaseScene, {"simulation.dimension=3.0"},
                     {"simulation.dimension", "expected an integer"});
}

TEST(SceneRules, FormatRequired) {
  expect_scene_error(replaced(kBaseScene, "format = \"tmdem-scene-1\"", ""),
                     {"format", "required", "tmdem-scene-1"});
}

TEST(SceneRules, FormatMustMatch) {
  expect_scene_error(kBaseScene, {"format=\"tmdem-scene-2\""},
                     {"format", "must be \"tmdem-scene-1\"", "tmdem-scene-2"});
}

TEST(SceneRules, DurationRequired) {
  expect_scene_error(replaced(kBaseScene, "duration = 10", ""),
                     {"simulation.duration", "required key is missing"});
  expect_scene_error(replaced(kBaseScene, "[simulation]\nduration = 10", ""),
                     {"simulation.duration", "required key is missing"});
}

TEST(SceneRules, DurationPositive) {
  expect_scene_error(kBaseScene, {"simulation.duration=0"},
                     {"simulation.duration", "must be > 0", "got 0"});
}

TEST(SceneRules, NaNRefused) {
  expect_scene_error(kBaseScene, {"material[0].density=nan"},
                     {"material[0].density", "finite", "nan"});
}

TEST(SceneRules, InfinityRefused) {
  expect_scene_error(kBaseScene, {"simulation.duration=inf"}, {"simulation.duration", "finite"});
  expect_scene_error(kBaseScene, {"simulation.gravity=[0, -inf, 0]"},
                     {"simulation.gravity[1]", "finite"});
}

TEST(SceneRules, RadiusPositive) {
  expect_scene_error(kBaseScene, {"particle[1].radius=0"}, {"particle[1].radius", "must be > 0"});
  expect_scene_error(kBaseScene, {"particle[0].radius=-0.001"},
                     {"particle[0].radius", "must be > 0"});
}

TEST(SceneRules, MaterialPropertiesPositive) {
  for (const char* key : {"density", "young_modulus", "conductivity", "heat_capacity"}) {
    SCOPED_TRACE(key);
    const std::string path = std::string("material[1].") + key;
    expect_scene_error(kBaseScene, {path + "=-5"}, {path, "must be > 0", "got -5"});
    expect_scene_error(kBaseScene, {path + "=0"}, {path, "must be > 0"});
  }
}

// thermal.contact_flattening: 0 by default, in [0, 1], and only with the Hertz law (the constant
// law has no spot to flatten), naming the key.
TEST(SceneRules, ContactFlatteningKey) {
  EXPECT_EQ(load_scene_text(kBaseScene, "t").thermal.contact_flattening, 0.0);
  EXPECT_EQ(load_scene_text(kBaseScene, "t", {"thermal.contact_flattening=0.025"}).thermal.contact_flattening,
            0.025);
  for (const char* f : {"-0.1", "1.5"})
    expect_scene_error(kBaseScene, {std::string("thermal.contact_flattening=") + f},
                       {"thermal.contact_flattening"});
  expect_scene_error(kBaseScene, {"thermal.contact_flattening=0.025", "thermal.conductance=\"constant\""},
                     {"thermal.contact_flattening", "constant", "hertz"});
  // 0 with the constant law is fine.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"thermal.contact_flattening=0.0", "thermal.conductance=\"constant\""}));
}

// thermal.particle_resistance ("off" by default) and thermal.core_fraction in (0, 1); refused
// with a conductivity table (the shell would follow k(T)), naming the key and the material.
TEST(SceneRules, ParticleResistanceKeys) {
  const Scene plain = load_scene_text(kBaseScene, "t");
  EXPECT_EQ(plain.thermal.particle_resistance, thermal::ParticleResistanceKind::Off);
  EXPECT_EQ(plain.thermal.core_fraction, 0.5);
  const Scene on = load_scene_text(
      kBaseScene, "t", {"thermal.particle_resistance=\"isothermal_core\"", "thermal.core_fraction=0.3"});
  EXPECT_EQ(on.thermal.particle_resistance, thermal::ParticleResistanceKind::IsothermalCore);
  EXPECT_EQ(on.thermal.core_fraction, 0.3);
  expect_scene_error(kBaseScene, {"thermal.particle_resistance=\"shell\""},
                     {"thermal.particle_resistance", "shell", "isothermal_core", "isothermal_core_rays"});
  // The rays are the surrounding layer's: refused with the Vargas-McCarthy gas, naming both keys.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                  {"thermal.particle_resistance=\"isothermal_core_rays\"",
                                   "effects.gas_conduction=true", "fluid.model=\"surrounding_layer\""}));
  expect_scene_error(kBaseScene,
                     {"thermal.particle_resistance=\"isothermal_core_rays\"", "effects.gas_conduction=true",
                      "fluid.model=\"vargas_mccarthy\""},
                     {"thermal.particle_resistance", "fluid.model", "vargas_mccarthy"});
  for (const char* c : {"0.0", "1.0", "1.5"})
    expect_scene_error(kBaseScene, {std::string("thermal.core_fraction=") + c}, {"thermal.core_fraction"});
  expect_scene_error(kBaseScene,
                     {"thermal.particle_resistance=\"isothermal_core\"",
                      "material[1].conductivity=[[250.0, 2.0], [400, 3.5]]"},
                     {"thermal.particle_resistance", "isothermal_core", "glass", "conductivity as a table"});
  // Off, the table is fine.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"material[1].conductivity=[[250.0, 2.0], [400, 3.5]]"}));
}

// conductivity and heat_capacity may be tables [[T_K, value], ...]: read as given (first value
// the reference), refused with the entry named when malformed.
TEST(SceneRules, MaterialPropertyTables) {
  for (const char* key : {"conductivity", "heat_capacity"}) {
    SCOPED_TRACE(key);
    const std::string path = std::string("material[1].") + key;
    const Scene scene =
        load_scene_text(kBaseScene, "t", {path + "=[[250.0, 2.0], [400, 3.5], [600, 4.0]]"});
    const Material& m = scene.materials[1];
    const auto& table = std::string(key) == "conductivity" ? m.conductivity_table : m.heat_capacity_table;
    ASSERT_EQ(table.size(), 3u);
    EXPECT_EQ(table[1][0], 400.0);
    EXPECT_EQ(table[1][1], 3.5);
    EXPECT_EQ(std::string(key) == "conductivity" ? m.conductivity_W_per_mK : m.heat_capacity_J_per_kgK, 2.0);
    EXPECT_TRUE(m.temperature_dependent());
    EXPECT_FALSE(scene.materials[0].temperature_dependent());
    expect_scene_error(kBaseScene, {path + "=[[300.0, 2.0], [300.0, 3.0]]"},
                       {path, "entry 1", "increase strictly"});
    expect_scene_error(kBaseScene, {path + "=[[300.0, -2.0]]"}, {path, "entry 0", "value > 0"});
    expect_scene_error(kBaseScene, {path + "=[[300.0]]"}, {path, "entry 0", "[T_K, value]"});
    expect_scene_error(kBaseScene, {path + "=[]"}, {path, "at least one"});
  }
}

TEST(SceneRules, MaterialRequiredKeys) {
  for (const char* key :
       {"name", "density", "young_modulus", "poisson_ratio", "conductivity", "heat_capacity"}) {
    SCOPED_TRACE(key);
    const std::string text = R"(format = "tmdem-scene-1"
[simulation]
duration = 1
[[material]]
)" + std::string(key == std::string("name") ? "" : "name = \"m\"\n") +
                             (key == std::string("density") ? "" : "density = 1.0\n") +
                             (key == std::string("young_modulus") ? "" : "young_modulus = 1.0\n") +
                             (key == std::string("poisson_ratio") ? "" : "poisson_ratio = 0.1\n") +
                             (key == std::string("conductivity") ? "" : "conductivity = 1.0\n") +
                             (key == std::string("heat_capacity") ? "" : "heat_capacity = 1.0\n") +
                             "[[particle]]\nposition = [0,0,0]\nradius = 1.0\nmaterial = \"m\"\n";
    expect_scene_error(text, {std::string("material[0].") + key, "required key is missing"});
  }
}

TEST(SceneRules, PoissonRatioOpenInterval) {
  expect_scene_error(kBaseScene, {"material[1].poisson_ratio=0.5"},
                     {"material[1].poisson_ratio", "must be in (-1, 0.5)", "got 0.5"});
  expect_scene_error(kBaseScene, {"material[0].poisson_ratio=-1"},
                     {"material[0].poisson_ratio", "(-1, 0.5)"});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"material[0].poisson_ratio=-0.99"}));
}

TEST(SceneRules, EmissivityClosedInterval) {
  expect_scene_error(kBaseScene, {"material[1].emissivity=1.5"},
                     {"material[1].emissivity", "must be in [0, 1]", "got 1.5"});
  expect_scene_error(kBaseScene, {"material[1].emissivity=-0.1"},
                     {"material[1].emissivity", "[0, 1]"});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"material[1].emissivity=1"}));
}

TEST(SceneRules, FrictionNonNegative) {
  expect_scene_error(kBaseScene, {"material[1].friction=-0.1"},
                     {"material[1].friction", "must be >= 0"});
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"material[1].friction=0"}));
}

// Rolling resistance: a coefficient in [0, 1], reaches the material, with every solver.
TEST(SceneRules, RollingFriction) {
  expect_scene_error(kBaseScene, {"material[1].rolling_friction=-0.1"},
                     {"material[1].rolling_friction"});
  const Scene scene = load_scene_text(kBaseScene, "t", {"material[1].rolling_friction=0.05"});
  EXPECT_EQ(scene.materials[1].rolling_friction, 0.05);
  EXPECT_EQ(scene.materials[0].rolling_friction, 0.0);
  for (const char* solver : {"nlgs", "nlgs_coloured", "apgd"}) {
    EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                    {"material[1].rolling_friction=0.05",
                                     std::string("mechanics.solver=\"") + solver + "\""}))
        << solver;
  }
}

TEST(SceneRules, DuplicateMaterialName) {
  expect_scene_error(kBaseScene, {"material[1].name=\"steel\""},
                     {"material[1].name", "duplicate", "material[0]"});
}

TEST(SceneRules, UnknownMaterialName) {
  expect_scene_error(kBaseScene, {"particle[0].material=\"stel\""},
                     {"particle[0].material", "unknown material \"stel\"", "\"steel\", \"glass\""});
  expect_scene_error(kBaseScene, {"wall[0].material=\"wood\""}, {"wall[0].material", "wood"});
}

TEST(SceneRules, OverlappingParticlesNamed) {
  expect_scene_error(kBaseScene, {"particle[1].position=[0.0015, 0.001, 0.0]"},
                     {"particles 0 and 1 overlap", "particle[0]", "particle[1]"});
}

TEST(SceneRules, TouchingParticlesAreNotOverlapping) {
  // Gap of -0.5e-9 of the radius is within the tolerance.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"particle[1].position=[0.0019999999995, 0.001, 0]"}));
}

TEST(SceneRules, ParticleBehindWall) {
  expect_scene_error(kBaseScene, {"particle[1].position=[0.002, 0.0005, 0.0]"},
                     {"particle 1", "wall[0]", "overlap"});
}

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

TEST(SceneRules, WallNormalNonZeroAndNormalized) {
  expect_scene_error(kBaseScene, {"wall[0].normal=[0, 0, 0]"}, {"wall[0].normal", "non-zero"});
  const Scene scene = load_scene_text(kBaseScene, "t", {"wall[0].normal=[0, 2, 0]"});
  EXPECT_DOUBLE_EQ(scene.walls[0].normal[1], 1.0);
}

TEST(SceneRules, WallTemperaturePositive) {
  expect_scene_error(kBaseScene, {"wall[0].temperature=-3"}, {"wall[0].temperature", "> 0"});
  const Scene scene = load_scene_text(kBaseScene, "t", {"wall[0].temperature=350"});
  ASSERT_TRUE(scene.walls[0].temperature_K.has_value());
  EXPECT_DOUBLE_EQ(*scene.walls[0].temperature_K, 350.0);
  EXPECT_FALSE(load_scene_text(kBaseScene, "t").walls[0].temperature_K.has_value());
}

TEST(SceneRules, ParticleTemperaturePositive) {
  expect_scene_error(kBaseScene, {"particle[1].temperature=0"},
                     {"particle[1].temperature", "must be > 0"});
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

TEST(SceneRules, IntegerWhereFloatExpected) {
  const Scene scene = load_scene_text(kBaseScene, "t", {"mechanics.theta=1"});
  EXPECT_DOUBLE_EQ(scene.duration_s, 10.0);
  EXPECT_DOUBLE_EQ(scene.mechanics.theta, 1.0);
}

TEST(SceneRules, SwitchedOffSectionAcceptedAndIgnored) {
  const std::string text = kBaseScene +
                           "\n[convection]\ncoefficient = -5.0\n[radiation]\n"
                           "ambient_temperature = -1.0\n";
  EXPECT_NO_THROW(load_scene_text(text, "t"));
  expect_scene_error(text, {"effects.convection=true"}, {"convection.coefficient", ">= 0"});
  expect_scene_error(text, {"effects.radiation=true"},
                     {"radiation.ambient_temperature", ">= 0"});
  // Still checked for unknown keys and types.
  expect_scene_error(kBaseScene + "\n[convection]\ncoeficient = 5.0\n",
                     {"convection.coeficient", "unknown key"});
  expect_scene_error(kBaseScene + "\n[convection]\ncoefficient = \"high\"\n",
                     {"convection.coefficient", "expected a number"});
  // [mechanics] is ignored when mechanics is off.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t",
                                  {"effects.mechanics=off", "thermal.conductance=constant",
                                   "mechanics.time_step=-1"}));
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

TEST(SceneRules, NoParticles) {
  const std::string text = "format = \"tmdem-scene-1\"\n[simulation]\nduration = 1\n";
  expect_scene_error(text, {"no particles"});
}

TEST(SceneRules, ParticleRequiredKeys) {
  expect_scene_error(replaced(kBaseScene, "position = [0.0, 0.001, 0.0]\n", ""),
                     {"particle[0].position", "required key is missing"});
  expect_scene_error(replaced(kBaseScene, "radius = 0.001\nmaterial = \"glass\"",
                              "material = \"glass\""),
                     {"particle[1].radius", "required key is missing"});
  expect_scene_error(replaced(kBaseScene, "radius = 0.001\nmaterial = \"glass\"", "radius = 0.001"),
                     {"particle[1].material", "required key is missing"});
}

TEST(SceneRules, VectorShape) {
  expect_scene_error(kBaseScene, {"particle[0].position=[0, 1]"},
                     {"particle[0].position", "3 numbers", "2 elements"});
  expect_scene_error(kBaseScene, {"particle[0].position=[0, \"a\", 1]"},
                     {"particle[0].position[1]", "expected a number"});
  // In 2D two components are enough (z = 0).
  const Scene scene = load_scene_text(kBaseScene, "t",
                                      {"simulation.dimension=2", "particle[0].position=[0, 0.001]"});
  EXPECT_EQ(scene.particles[0].position_m[2], 0.0);
}

TEST(SceneRules, GeneratorErrors) {
  const std::string triangle =
      base_scene().add("generate", triangular({3, 2}, {{"origin", {0.0, 0.01, 0.0}}}));
  EXPECT_NO_THROW(load_scene_text(triangle, "t"));
  expect_scene_error(triangle, {"generate[0].rows=[3, 0]"}, {"generate[0].rows[1]", "must be in [1, 10000000] (got 0)"});
  expect_scene_error(triangle, {"generate[0].radius=0"}, {"generate[0].radius", "> 0"});
  expect_scene_error(triangle, {"generate[0].kind=hexagonal"},
                     {"generate[0].kind", "\"triangular\", \"column\", \"lattice\", \"random\""});
  expect_scene_error(triangle, {"generate[0].kind=column"},
                     {"generate[0].rows", "not a key of kind = \"column\"", "count, radius"});
  expect_scene_error(triangle, {"generate[0].material=\"wood\""},
                     {"generate[0].material", "unknown material"});
  expect_scene_error(replaced(triangle, "kind = \"triangular\"\n", ""),
                     {"generate[0].kind", "required"});
  expect_scene_error(triangle, {"generate[0].origin=[0.0, 0.001, 0.0]"},
                     {"particles 0 and 2 overlap", "generate[0]"});
}

TEST(SceneRules, LatticeSpacingBelowDiameter) {
  const std::string lattice =
      base_scene().add("generate", tmdem::test::lattice({2, 2, 2}, {{"origin", {0.0, 0.01, 0.0}}}));
  EXPECT_NO_THROW(load_scene_text(lattice, "t"));
  expect_scene_error(lattice, {"generate[0].spacing=0.0019"},
                     {"generate[0].spacing", "must be >= 2 * radius"});
  expect_scene_error(lattice, {"generate[0].counts=[2, 2]"},
                     {"generate[0].counts", "3 integers"});
  expect_scene_error(lattice, {"simulation.dimension=2"}, {"generate[0].counts", "nz must be 1"});
}

TEST(SceneRules, RandomGeneratorKeys) {
  const std::string random = base_scene().add(
      "generate", random_fill(10, "{ min = [0.0, 0.01, 0.0], max = [0.01, 0.02, 0.01] }",
                              {{"radii", {0.0005, 0.001}}, {"fractions", {0.5, 0.5}}}));
  expect_scene_error(random, {"generate[0].fractions=[0.5, 0.4]"},
                     {"generate[0].fractions", "sum to 1"});
  expect_scene_error(random, {"generate[0].fractions=[1.0]"},
                     {"generate[0].fractions", "as many entries as radii"});
  expect_scene_error(random, {"generate[0].radius=0.001"}, {"generate[0]", "either radius or radii"});
  expect_scene_error(random, {"generate[0].radii=[0.001, -0.001]"}, {"generate[0].radii[1]", "> 0"});
  expect_scene_error(random, {"generate[0].count=0"}, {"generate[0].count", "must be an integer in [1, 10000000] (got 0)"});
  expect_scene_error(random, {"generate[0].box.max=[0.01, 0.0, 0.01]"},
                     {"generate[0].box.max", "must be >= min"});
  expect_scene_error(replaced(random, "box = { min = [0.0, 0.01, 0.0], max = [0.01, 0.02, 0.01] }\n", ""),
                     {"generate[0].box", "required"});
}

TEST(SceneRules, AssignErrors) {
  const std::string base = kBaseScene + "\n[[assign]]\nids = [1]\ntemperature = 350.0\n";
  EXPECT_NO_THROW(load_scene_text(base, "t"));
  expect_scene_error(base, {"assign[0].ids=[0, 2]"},
                     {"assign[0].ids[1]", "particle id 2 does not exist", "2 particles"});
  expect_scene_error(base, {"assign[0].ids=[-1]"}, {"assign[0].ids[0]", ">= 0"});
  expect_scene_error(base, {"assign[0].nearest={ point = [0,0,0], count = 1 }"},
                     {"assign[0]", "exactly one selector"});
  expect_scene_error(kBaseScene + "\n[[assign]]\ntemperature = 350.0\n",
                     {"assign[0]", "exactly one selector"});
  expect_scene_error(kBaseScene + "\n[[assign]]\nids = [0]\n", {"assign[0]", "sets nothing"});
  expect_scene_error(base, {"assign[0].material=\"wood\""}, {"assign[0].material", "wood"});
  expect_scene_error(base, {"assign[0].temperature=-1"}, {"assign[0].temperature", "> 0"});
  expect_scene_error(kBaseScene + "\n[[assign]]\nnearest = { point = [0,0,0], count = 3 }\n"
                                  "fixed = true\n",
                     {"assign[0].nearest.count", "at most the number of particles, 2"});
  expect_scene_error(kBaseScene + "\n[[assign]]\nbox = { min = [5,5,5], max = [6,6,6] }\n"
                                  "fixed = true\n",
                     {"assign[0].box", "selects no particle"});
}

}  // namespace
}  // namespace tmdem::coupling::test
