// Validation rules of contract section 2 on what the scene is made of: materials and their
// properties, particles (required keys, overlaps, walls behind them, temperatures), walls and the
// generators. Loading throws SceneError and the message names the key path (and the allowed
// values or range).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "tests/coupling/SceneTestUtil.h"
#include "tests/coupling/scene/SceneRulesText.h"

namespace tmdem::coupling::test {
namespace {

using namespace scene_rules;

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
