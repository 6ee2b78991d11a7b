#pragma once
// Helpers shared by the test_scene_*.cpp files.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"

namespace tmdem::coupling::test {

// A small valid 3D scene: two materials, two touching particles, a floor.
inline const std::string kBaseScene = R"(format = "tmdem-scene-1"

[simulation]
duration = 10

[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
conductivity = 50.0
heat_capacity = 460.0

[[material]]
name = "glass"
density = 2500.0
young_modulus = 6.3e10
poisson_ratio = 0.2
friction = 0.5
conductivity = 1.0
heat_capacity = 840.0
emissivity = 0.9

[[particle]]
position = [0.0, 0.001, 0.0]
radius = 0.001
material = "steel"

[[particle]]
position = [0.002, 0.001, 0.0]
radius = 0.001
material = "glass"
temperature = 300.0

[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "steel"
)";

// The SceneError message of loading `text` with `overrides`; a test failure if it loads.
inline std::string scene_error(std::string_view text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_text(text, "test.toml", overrides);
  } catch (const SceneError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "not a SceneError: " << error.what();
    return {};
  }
  ADD_FAILURE() << "the scene loaded without error";
  return {};
}

// Loading fails with a SceneError whose message contains every part.
inline void expect_scene_error(std::string_view text, const std::vector<std::string>& overrides,
                               std::initializer_list<std::string_view> parts) {
  const std::string message = scene_error(text, overrides);
  for (const auto part : parts)
    EXPECT_NE(message.find(part), std::string::npos)
        << "message does not contain \"" << part << "\":\n  " << message;
}

inline void expect_scene_error(std::string_view text,
                               std::initializer_list<std::string_view> parts) {
  expect_scene_error(text, {}, parts);
}

}  // namespace tmdem::coupling::test
