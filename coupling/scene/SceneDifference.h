#pragma once
// Compares two resolved scenes (Scene::resolved_toml) key by key, so a restart can refuse a
// scene that is not the one its checkpoint ran. Keys that only extend or observe the run
// (simulation.duration and everything under output) are not compared. The resolved scene holds
// the keys as written plus the --set overrides, not the defaults: a key written in one scene and
// left to its default in the other counts as a difference.
#include <optional>
#include <string>

namespace tmdem::coupling {

struct SceneDifference {
  std::string key;           // dotted key path, arrays of tables indexed: "generate[0].radius"
  std::string before_value;  // inline TOML text of the first scene's value, or "(absent)"
  std::string after_value;   // the same for the second scene
};

// The first difference in key order (tables sorted by key), or nothing when the scenes agree
// on every compared key. Throws SceneError if either text is not valid TOML.
std::optional<SceneDifference> first_scene_difference(const std::string& before_toml,
                                                      const std::string& after_toml);

// Whether a restart may change this key path (simulation.duration, output and below).
bool restart_may_change(const std::string& key);

}  // namespace tmdem::coupling
