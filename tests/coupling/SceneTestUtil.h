#pragma once
// Helpers shared by the test_scene_*.cpp files.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling::test {

using namespace tmdem::test;

// A small valid 3D scene: two materials, two touching particles, a floor.
inline SceneBuilder base_scene() {
  return SceneBuilder()
      .set("simulation.duration", 10)
      .add("material", steel())
      .add("material", glass({{"friction", 0.5}, {"emissivity", 0.9}}))
      .add("particle", particle({0.0, 0.001, 0.0}))
      .add("particle", particle({0.002, 0.001, 0.0}, {{"material", "glass"}, {"temperature", 300.0}}))
      .add("wall", floor_wall());
}
inline const std::string kBaseScene = base_scene();

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
