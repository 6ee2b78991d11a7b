// Each default of [simulation], [mechanics], [thermal], [output] and of a new particle is written
// once, in Scene.h's structs; the schema takes it from there for the reference (`tmdem docs
// scene`, docs/scene.md). These tests hold the two together from the outside: a scene that states
// a key at the default the reference prints loads to exactly what the structs hold, and so does a
// scene that leaves every key out. A literal written again in the schema (or read with its own
// fallback by the loader) that disagrees with the struct fails here.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "coupling/scene/SceneSchema.h"
#include "../SceneTestUtil.h"

namespace tmdem::coupling::test {

namespace {

// True when `scene`'s settings sections all hold the structs' defaults.
::testing::AssertionResult settings_at_struct_defaults(const Scene& scene) {
  const Scene defaults;
  if (!(scene.mechanics == MechanicsSettings{})) return ::testing::AssertionFailure() << "[mechanics] differs";
  if (!(scene.thermal == ThermalSettings{})) return ::testing::AssertionFailure() << "[thermal] differs";
  if (!(scene.output == OutputSettings{})) return ::testing::AssertionFailure() << "[output] differs";
  if (scene.dimension != defaults.dimension || scene.seed != defaults.seed)
    return ::testing::AssertionFailure() << "simulation.dimension or seed differs";
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(SceneDefaults, AbsentKeysLoadToTheStructDefaults) {
  EXPECT_TRUE(settings_at_struct_defaults(load_scene_text(kBaseScene, "test.toml")));
}

TEST(SceneDefaults, EveryDefaultTheReferenceStatesLoadsToTheStructDefault) {
  std::set<std::string> without_default;
  int checked = 0;
  for (const char* section : {"simulation", "mechanics", "thermal", "output"}) {
    for (const auto& key : *SceneSchema::keys(section)) {
      const std::string path = std::string(section) + "." + key.name;
      if (key.default_text.empty()) {
        without_default.insert(path);
        continue;
      }
      // The reference's text, given as the scene's value.
      const Scene given = load_scene_text(kBaseScene, "test.toml", {path + "=" + key.default_text});
      EXPECT_TRUE(settings_at_struct_defaults(given)) << path << " = " << key.default_text;
      ++checked;
    }
  }
  // Keys without a default are the required ones and those whose absence means "automatic".
  EXPECT_EQ(without_default, (std::set<std::string>{"simulation.duration", "mechanics.fall_speed",
                                                    "mechanics.compaction_speed"}));
  EXPECT_GE(checked, 35);
}

// gravity's "[0, 0, 0]" (loaded above as a --set) is also what an absent gravity gives, and
// fall_speed's absence ("automatic") is the struct's zero.
TEST(SceneDefaults, AbsentVectorsAndAutomaticValuesAreTheStructZeros) {
  const Scene scene = load_scene_text(kBaseScene, "test.toml");
  EXPECT_EQ(scene.gravity_m_per_s2, Scene{}.gravity_m_per_s2);
  EXPECT_EQ(SceneSchema::find("simulation", "gravity")->default_text, "[0, 0, 0]");
  EXPECT_EQ(scene.mechanics.fall_speed_m_per_s, 0.0);
}

// A new particle's temperature, holding, source and fixing: the reference's defaults are
// Particle's, and a particle that states them loads to the same particle as one that does not.
TEST(SceneDefaults, ParticleDefaultsAreTheStructs) {
  const Particle fresh;
  const Scene plain = load_scene_text(kBaseScene, "test.toml");
  EXPECT_EQ(plain.particles[0].temperature_K, fresh.temperature_K);
  EXPECT_EQ(plain.particles[0].fixed_temperature, fresh.fixed_temperature);
  EXPECT_EQ(plain.particles[0].heat_source_W, fresh.heat_source_W);
  EXPECT_EQ(plain.particles[0].fixed, fresh.fixed);
  for (const char* name : {"temperature", "fixed_temperature", "heat_source", "fixed"}) {
    const auto* key = SceneSchema::find("particle", name);
    ASSERT_NE(key, nullptr) << name;
    EXPECT_EQ(key->default_text, SceneSchema::find("generate", name)->default_text) << name;
    const Scene stated =
        load_scene_text(kBaseScene + "\n[[particle]]\nposition = [0.0, 0.004, 0.0]\nradius = 0.001\n"
                                     "material = \"steel\"\n" + name + " = " + key->default_text + "\n",
                        "test.toml");
    const Particle& p = stated.particles.back();
    EXPECT_EQ(p.temperature_K, fresh.temperature_K) << name;
    EXPECT_EQ(p.fixed_temperature, fresh.fixed_temperature) << name;
    EXPECT_EQ(p.heat_source_W, fresh.heat_source_W) << name;
    EXPECT_EQ(p.fixed, fresh.fixed) << name;
  }
}

// A [[material]]'s optional keys: the reference's defaults are Material's (Scene.h), and a
// material that states one at that default loads to the same material as one that leaves it
// out (the base scene's steel states none of them).
TEST(SceneDefaults, MaterialDefaultsAreTheStructs) {
  const Material fresh;
  auto optional_fields = [](const Material& m) {
    return std::vector<double>{m.friction, m.rolling_friction, m.emissivity, m.thermal_expansion_per_K,
                               m.roughness_m, m.asperity_slope};
  };
  const Scene plain = load_scene_text(kBaseScene, "test.toml");
  ASSERT_EQ(plain.materials[0].name, "steel");
  EXPECT_EQ(optional_fields(plain.materials[0]), optional_fields(fresh));
  EXPECT_EQ(fresh.friction, 0.3);  // what scenes without a friction key have always had
  int checked = 0;
  for (const auto& key : *SceneSchema::keys("material")) {
    if (key.required || key.default_text.empty()) continue;
    const Scene stated = load_scene_text(kBaseScene, "test.toml", {"material[0]." + key.name + "=" + key.default_text});
    EXPECT_EQ(optional_fields(stated.materials[0]), optional_fields(fresh)) << key.name << " = " << key.default_text;
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

}  // namespace tmdem::coupling::test

namespace tmdem::coupling::test {

// The scene's choices of thermal.conductance and thermal.particle_resistance are the kinds'
// names (one list, next to each enum), and a name the scene accepts loads to its kind.
TEST(SceneKinds, ThermalChoicesAreTheKindsNames) {
  const auto* conductance = SceneSchema::find("thermal", "conductance");
  ASSERT_NE(conductance, nullptr);
  EXPECT_EQ(conductance->choices, (std::vector<std::string>{"hertz", "constant", "bahrami"}));
  const auto* resistance = SceneSchema::find("thermal", "particle_resistance");
  ASSERT_NE(resistance, nullptr);
  EXPECT_EQ(resistance->choices,
            (std::vector<std::string>{"off", "isothermal_core", "isothermal_core_rays"}));
  const Scene constant = load_scene_text(kBaseScene, "test.toml", {"thermal.conductance=\"constant\""});
  EXPECT_EQ(constant.thermal.conductance, thermal::ConductanceLawKind::Constant);
  expect_scene_error(kBaseScene, {"thermal.conductance=\"linear\""},
                     {"thermal.conductance", "\"linear\"", "\"hertz\", \"constant\", \"bahrami\""});
}

}  // namespace tmdem::coupling::test
