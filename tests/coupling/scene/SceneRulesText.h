#pragma once
// What the scene-rule tests share (test_scene_rules_syntax, _bodies and _settings.cpp): a scene
// text with one piece of it replaced.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

namespace tmdem::coupling::test::scene_rules {

// `text` with the first `from` replaced by `to`; a failure if `from` is not in it.
inline std::string replaced(std::string text, std::string_view from, std::string_view to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace tmdem::coupling::test::scene_rules
