#include "coupling/scene/SceneDifference.h"

#include <algorithm>
#include <set>

#include <toml++/toml.h>

#include "coupling/scene/SceneError.h"
#include "coupling/scene/TomlWriter.h"

namespace tmdem::coupling {

namespace {

constexpr const char* kAbsent = "(absent)";

toml::table parse_scene(const std::string& text, const char* which) {
  try {
    return toml::parse(text, std::string_view(which));
  } catch (const toml::parse_error& error) {
    throw SceneError(std::string(which) + ": not valid TOML: " + std::string(error.description()));
  }
}

std::optional<SceneDifference> compare(const toml::node* a, const toml::node* b,
                                       const std::string& key);

std::optional<SceneDifference> compare_tables(const toml::table& a, const toml::table& b,
                                              const std::string& prefix) {
  std::set<std::string> keys;
  for (const auto& [k, v] : a) keys.insert(std::string(k.str()));
  for (const auto& [k, v] : b) keys.insert(std::string(k.str()));
  for (const std::string& k : keys) {
    const std::string key = prefix.empty() ? k : prefix + "." + k;
    if (restart_may_change(key)) continue;
    if (auto difference = compare(a.get(k), b.get(k), key)) return difference;
  }
  return std::nullopt;
}

std::optional<SceneDifference> compare(const toml::node* a, const toml::node* b,
                                       const std::string& key) {
  if (a == nullptr || b == nullptr) {
    if (a == nullptr && b == nullptr) return std::nullopt;
    return SceneDifference{key, a ? write_toml_value(*a) : kAbsent,
                           b ? write_toml_value(*b) : kAbsent};
  }
  if (a->is_table() && b->is_table()) return compare_tables(*a->as_table(), *b->as_table(), key);
  const auto* array_a = a->as_array();
  const auto* array_b = b->as_array();
  if (array_a && array_b && array_a->is_array_of_tables() && array_b->is_array_of_tables() &&
      !array_a->empty() && !array_b->empty()) {
    // Arrays of tables ([[generate]], [[material]]) are compared entry by entry so the message
    // names the key inside the entry.
    const std::size_t n = std::max(array_a->size(), array_b->size());
    for (std::size_t i = 0; i < n; ++i) {
      const std::string entry = key + "[" + std::to_string(i) + "]";
      if (auto difference = compare(array_a->get(i), array_b->get(i), entry)) return difference;
    }
    return std::nullopt;
  }
  // Leaves and plain arrays: the shortest exact text of equal values is equal, and of unequal
  // values (another type, another double) differs.
  std::string text_a = write_toml_value(*a), text_b = write_toml_value(*b);
  if (text_a == text_b) return std::nullopt;
  return SceneDifference{key, std::move(text_a), std::move(text_b)};
}

}  // namespace

bool restart_may_change(const std::string& key) {
  return key == "simulation.duration" || key == "output" || key.rfind("output.", 0) == 0;
}

std::optional<SceneDifference> first_scene_difference(const std::string& before_toml,
                                                      const std::string& after_toml) {
  const toml::table before = parse_scene(before_toml, "checkpoint scene");
  const toml::table after = parse_scene(after_toml, "scene");
  return compare_tables(before, after, "");
}

}  // namespace tmdem::coupling
