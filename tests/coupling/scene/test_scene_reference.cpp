// docs/scene.md is the generated scene reference: it must equal what `tmdem docs scene` prints
// from the schema the loader validates with, and it lists every mode's own keys.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "coupling/scene/SceneReference.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling::test {
namespace {

TEST(SceneReference, DocsSceneMdIsTheGeneratedReference) {
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/docs/scene.md");
  ASSERT_TRUE(in) << "docs/scene.md is missing; generate it with: build/tmdem docs scene > docs/scene.md";
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_TRUE(committed.str() == scene_reference_markdown())
      << "docs/scene.md differs from the schema; regenerate it with:\n"
         "  build/tmdem docs scene > docs/scene.md";
}

TEST(SceneReference, ListsEveryModesSectionKeysWithUnitDefaultAndRange) {
  const std::string text = scene_reference_markdown();
  for (const auto* mode : thermal::heat_transfer_modes()) {
    if (!mode->effect.empty()) {
      EXPECT_NE(text.find("| `" + std::string(mode->effect) + "` | - | " +
                          (mode->effect_default ? "true" : "false") + " | true, false |"),
                std::string::npos)
          << mode->effect;
    }
    if (mode->section.empty()) continue;
    EXPECT_NE(text.find("## `[" + std::string(mode->section) + "]`"), std::string::npos);
    for (const auto& p : mode->parameters) {
      std::string default_text = thermal::parameter_text(p.default_value);
      std::string allowed = p.range.interval();
      if (p.boolean) {
        default_text = p.default_value != 0.0 ? "true" : "false";
        allowed = "true, false";
      } else if (!p.choices.empty()) {
        default_text = "\"" + std::string(p.choices[std::size_t(p.default_value)]) + "\"";
        allowed.clear();
        for (const auto& c : p.choices) allowed += (allowed.empty() ? "\"" : ", \"") + std::string(c) + "\"";
      }
      EXPECT_NE(text.find("| `" + std::string(p.key) + "` | " +
                          (p.unit.empty() ? "-" : std::string(p.unit)) + " | " + default_text +
                          " | " + allowed + " | " + std::string(p.description) + " |"),
                std::string::npos)
          << mode->section << "." << p.key;
    }
  }
  EXPECT_NE(text.find("| `coefficient` | W/(m^2 K) | 10 | >= 0 |"), std::string::npos);
}

}  // namespace
}  // namespace tmdem::coupling::test
