// The heat-transfer modes seen from the scene: every mode's own declaration (effects key,
// section, parameters with unit, default and range) is in the schema the loader validates with,
// its keys are checked against the declared range only while its effect is on, and unknown
// effects name the valid ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "coupling/scene/HeatModes.h"
#include "coupling/scene/SceneSchema.h"
#include "tests/coupling/SceneTestUtil.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling::test {
namespace {

TEST(SceneModes, SchemaHoldsEveryModesEffectSectionAndKeys) {
  int parameters = 0;
  for (const auto* mode : thermal::heat_transfer_modes()) {
    if (!mode->effect.empty()) {
      const auto* key = SceneSchema::find("effects", mode->effect);
      ASSERT_NE(key, nullptr) << mode->name;
      EXPECT_EQ(key->default_text, mode->effect_default ? "true" : "false") << mode->name;
    }
    if (mode->section.empty()) continue;
    const auto* section = SceneSchema::find("", mode->section);
    ASSERT_NE(section, nullptr) << mode->section;
    EXPECT_EQ(section->kind, SceneSchema::Kind::Table);
    for (const auto& p : mode->parameters) {
      const auto* key = SceneSchema::find(mode->section, p.key);
      ASSERT_NE(key, nullptr) << mode->section << "." << p.key;
      EXPECT_EQ(key->unit, p.unit);
      EXPECT_EQ(key->description, p.description);
      ++parameters;
      if (p.boolean) {  // true/false in the scene
        EXPECT_EQ(key->allowed, "true, false");
        EXPECT_EQ(key->default_text, p.default_value != 0.0 ? "true" : "false");
        continue;
      }
      if (!p.choices.empty()) {  // a name out of the declared choices
        ASSERT_EQ(key->choices.size(), p.choices.size()) << p.key;
        for (std::size_t c = 0; c < p.choices.size(); ++c) EXPECT_EQ(key->choices[c], p.choices[c]);
        EXPECT_EQ(key->default_text,
                  "\"" + std::string(p.choices[std::size_t(p.default_value)]) + "\"");
        continue;
      }
      ASSERT_TRUE(key->default_number.has_value());
      EXPECT_EQ(*key->default_number, p.default_value);
      ASSERT_TRUE(key->range.has_value());
      EXPECT_EQ(key->allowed, p.range.interval());
    }
  }
  EXPECT_GE(parameters, 3);  // convection: coefficient, fluid_temperature; radiation: ambient
  // The contract's keys, spelled exactly.
  for (const auto& [section, key] :
       {std::pair{"convection", "coefficient"}, {"convection", "fluid_temperature"},
        {"radiation", "ambient_temperature"}, {"effects", "convection"}, {"effects", "radiation"},
        {"effects", "conduction"}})
    EXPECT_NE(SceneSchema::find(section, key), nullptr) << section << "." << key;
}

TEST(SceneModes, ModeDefaultsComeFromTheDeclaration) {
  const Scene scene = load_scene_text(kBaseScene, "test.toml");
  for (const auto* mode : thermal::heat_transfer_modes())
    for (const auto& p : mode->parameters)
      EXPECT_EQ(scene.heat_modes.find(mode->name, p.key), p.default_value)
          << mode->name << "." << p.key;
}

TEST(SceneModes, BadModeValueNamesKeyPathAndDeclaredRange) {
  expect_scene_error(kBaseScene, {"effects.convection=true", "convection.fluid_temperature=0"},
                     {"--set convection.fluid_temperature", "convection.fluid_temperature",
                      "must be > 0", "(got 0)"});
  expect_scene_error(kBaseScene, {"effects.radiation=true", "radiation.ambient_temperature=-1"},
                     {"radiation.ambient_temperature", "must be >= 0", "(got -1)"});
  // Off: the range is not enforced, the section is accepted and ignored (contract section 2).
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "test.toml", {"convection.fluid_temperature=0"}));
}

// [radiation] surroundings = false (an enclosed bed): the ambient mode is not built, pair
// radiation is; with pair radiation off too nothing would exchange, and the scene says so.
TEST(SceneModes, EnclosedRadiationBuildsNoAmbientModeAndNeedsPairRadiation) {
  const auto& ambient = *thermal::find_heat_transfer_mode("radiation");
  const auto& pairs = *thermal::find_heat_transfer_mode("particle_radiation");
  const Scene open = load_scene_text(kBaseScene, "test.toml", {"effects.radiation=true"});
  EXPECT_TRUE(mode_enabled(open, ambient));
  EXPECT_FALSE(mode_enabled(open, pairs));
  const Scene enclosed = load_scene_text(
      kBaseScene, "test.toml",
      {"effects.radiation=true", "radiation.between_particles=true", "radiation.surroundings=false"});
  EXPECT_FALSE(mode_enabled(enclosed, ambient));
  EXPECT_TRUE(mode_enabled(enclosed, pairs));
  expect_scene_error(kBaseScene, {"effects.radiation=true", "radiation.surroundings=false"},
                     {"radiation.surroundings", "nothing to exchange", "between_particles = true"});
}

TEST(SceneModes, UnknownEffectAndModeKeyListTheValidOnes) {
  std::string effects;
  for (const auto& e : thermal::heat_transfer_effects()) effects += ", " + std::string(e.key);
  expect_scene_error(kBaseScene + "\n[effects]\nconvecton = true\n",
                     {"effects.convecton", "did you mean convection",
                      "valid keys here: mechanics" + effects});
  expect_scene_error(kBaseScene + "\n[radiation]\nambient_temperatur = 300.0\n",
                     {"radiation.ambient_temperatur", "did you mean ambient_temperature",
                      "valid keys here: ambient_temperature"});
  expect_scene_error(kBaseScene, {"effects.gravity=true"},
                     {"unknown key effects.gravity", "mechanics" + effects});
}

}  // namespace
}  // namespace tmdem::coupling::test
