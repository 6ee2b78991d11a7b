#pragma once
// Scene TOML text for tests, built from a default so that a test states only what differs.
//
//   const std::string text = thermal_scene()               // steel, mechanics off, constant H
//       .set("simulation.duration", 20.0)
//       .add("generate", lattice({3, 3, 2}))
//       .add("assign", {{"ids", {0}}, {"temperature", 373.15}})
//       .add("wall", floor_wall({{"temperature", 350.0}}));
//
// Tables and array-of-table entries are written in the order they were first set or added,
// each key in its first position, so the text reads like a hand-written scene. Values are
// typed: a C string is a TOML string, a double always a TOML float (1.0, never 1), an int a
// TOML integer; raw() passes TOML text through (inline tables).
#include <algorithm>
#include <array>
#include <charconv>
#include <initializer_list>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tmdem::test {

// One TOML value as text.
class TomlValue {
 public:
  TomlValue(double x) : text_(number(x)) {}
  TomlValue(int x) : text_(std::to_string(x)) {}
  TomlValue(bool x) : text_(x ? "true" : "false") {}
  TomlValue(const char* s) : text_(quoted(s)) {}
  TomlValue(const std::string& s) : text_(quoted(s)) {}
  TomlValue(std::initializer_list<double> xs) : text_(array(xs)) {}
  TomlValue(std::initializer_list<int> xs) : text_(array(xs)) {}
  // TOML text as it stands, e.g. raw("{ min = [0, 0, 0], max = [1, 1, 1] }").
  static TomlValue raw(std::string text) {
    TomlValue v(0);
    v.text_ = std::move(text);
    return v;
  }
  const std::string& text() const { return text_; }

  // Shortest round-trip form, always a float: 7800.0, 0.001, 2.1e11, 1e-10.
  static std::string number(double x) {
    std::array<char, 64> buf{};
    const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), x).ptr;
    std::string s(buf.data(), end);
    const auto e = s.find('e');
    if (e != std::string::npos) {
      std::string exponent = s.substr(e + 1);
      const bool negative = exponent[0] == '-';
      if (exponent[0] == '+' || negative) exponent.erase(0, 1);
      exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
      return s.substr(0, e).append(negative ? "e-" : "e").append(exponent);
    }
    if (s.find_first_of(".in") == std::string::npos) s += ".0";  // not inf or nan
    return s;
  }

 private:
  static std::string quoted(std::string_view s) { return std::string("\"").append(s).append("\""); }
  template <class T>
  static std::string array(std::initializer_list<T> xs) {
    std::string s = "[";
    for (const T& x : xs) s.append(s.size() > 1 ? ", " : "").append(TomlValue(x).text());
    return s.append("]");
  }
  std::string text_;
};

inline TomlValue raw(std::string text) { return TomlValue::raw(std::move(text)); }

// The keys of one table, in order.
using TomlKeys = std::vector<std::pair<std::string, TomlValue>>;

// `base` with the keys of `changes` replaced in place or appended.
inline TomlKeys with(TomlKeys base, const TomlKeys& changes) {
  for (const auto& [key, value] : changes) {
    bool found = false;
    for (auto& entry : base)
      if (entry.first == key) {
        entry.second = value;
        found = true;
      }
    if (!found) base.emplace_back(key, value);
  }
  return base;
}

class SceneBuilder {
 public:
  // Only the format line; see the factories below for the usual starting points.
  SceneBuilder() { set("format", "tmdem-scene-1"); }

  // "section.key" or "array[i].key" (i-th entry added so far) or a top-level "key".
  SceneBuilder& set(std::string_view path, TomlValue value) {
    auto [block, key] = locate(path, true);
    for (auto& entry : block->keys)
      if (entry.first == key) {
        entry.second = std::move(value);
        return *this;
      }
    block->keys.emplace_back(std::string(key), std::move(value));
    return *this;
  }
  SceneBuilder& erase(std::string_view path) {
    const auto [block, key] = locate(path, false);
    const std::string_view name = key;  // clang 14 cannot capture a structured binding
    std::erase_if(block->keys, [name](const auto& entry) { return entry.first == name; });
    return *this;
  }
  // Sets each "section.key" of a list, in order.
  SceneBuilder& set(const TomlKeys& paths) {
    for (const auto& [path, value] : paths) set(path, value);
    return *this;
  }
  // Appends a [[array]] entry.
  SceneBuilder& add(std::string_view array, TomlKeys keys) {
    blocks_.push_back({std::string(array), true, std::move(keys)});
    return *this;
  }

  // The scene text: top-level keys, then each table with a blank line before its header.
  std::string str() const {
    std::string s;
    for (const auto& b : blocks_) {
      if (!b.name.empty()) s.append("\n").append(b.array ? "[[" : "[").append(b.name).append(b.array ? "]]\n" : "]\n");
      for (const auto& [key, value] : b.keys) s.append(key).append(" = ").append(value.text()).append("\n");
    }
    return s;
  }
  operator std::string() const { return str(); }

 private:
  struct Block {
    std::string name;  // "" for the top level
    bool array = false;
    TomlKeys keys;
  };

  std::pair<Block*, std::string_view> locate(std::string_view path, bool create) {
    const auto dot = path.find('.');
    if (dot == std::string_view::npos) return {top(), path};
    std::string_view table = path.substr(0, dot);
    const std::string_view key = path.substr(dot + 1);
    const auto bracket = table.find('[');
    if (bracket != std::string_view::npos) {
      const int index = std::stoi(std::string(table.substr(bracket + 1)));
      table = table.substr(0, bracket);
      int seen = 0;
      for (auto& b : blocks_)
        if (b.array && b.name == table && seen++ == index) return {&b, key};
      throw std::out_of_range("SceneBuilder: no entry " + std::string(path));
    }
    for (auto& b : blocks_)
      if (!b.array && b.name == table) return {&b, key};
    if (!create) throw std::out_of_range("SceneBuilder: no table " + std::string(table));
    blocks_.push_back({std::string(table), false, {}});
    return {&blocks_.back(), key};
  }
  Block* top() {
    if (blocks_.empty() || !blocks_.front().name.empty()) blocks_.insert(blocks_.begin(), Block{});
    return &blocks_.front();
  }

  std::vector<Block> blocks_;
};

inline std::ostream& operator<<(std::ostream& out, const SceneBuilder& scene) {
  return out << scene.str();
}

// ---- materials ----------------------------------------------------------------------------

inline TomlKeys steel(const TomlKeys& changes = {}) {
  return with({{"name", "steel"},
               {"density", 7800.0},
               {"young_modulus", 2.1e11},
               {"poisson_ratio", 0.3},
               {"conductivity", 50.0},
               {"heat_capacity", 460.0}},
              changes);
}

inline TomlKeys glass(const TomlKeys& changes = {}) {
  return with({{"name", "glass"},
               {"density", 2500.0},
               {"young_modulus", 6.3e10},
               {"poisson_ratio", 0.2},
               {"conductivity", 1.0},
               {"heat_capacity", 840.0}},
              changes);
}

inline TomlKeys copper(const TomlKeys& changes = {}) {
  return with({{"name", "copper"},
               {"density", 8900.0},
               {"young_modulus", 1.2e11},
               {"poisson_ratio", 0.34},
               {"conductivity", 400.0},
               {"heat_capacity", 385.0}},
              changes);
}

// ---- particles, generators, walls ---------------------------------------------------------

// Touching 1 mm steel spheres 2 mm apart from (1, 1, 1) mm, x fastest.
// Generated particles start at the loader's default 293.15 K.
inline TomlKeys lattice(std::initializer_list<int> counts, const TomlKeys& changes = {}) {
  return with({{"kind", "lattice"},
               {"counts", counts},
               {"spacing", 0.002},
               {"radius", 0.001},
               {"origin", {0.001, 0.001, 0.001}},
               {"material", "steel"}},
              changes);
}

// A vertical stack of touching 1 mm steel spheres resting on y = 0.
inline TomlKeys column(int count, const TomlKeys& changes = {}) {
  return with({{"kind", "column"},
               {"count", count},
               {"radius", 0.001},
               {"origin", {0.0, 0.001, 0.0}},
               {"material", "steel"}},
              changes);
}

// Rows of touching 1 mm steel spheres on a triangular lattice, bottom row first.
inline TomlKeys triangular(std::initializer_list<int> rows, const TomlKeys& changes = {}) {
  return with({{"kind", "triangular"},
               {"rows", rows},
               {"radius", 0.001},
               {"origin", {0.001, 0.001, 0.0}},
               {"material", "steel"}},
              changes);
}

// `count` steel spheres placed at random in `box`, an inline table "{ min = [..], max = [..] }";
// changes give radius or radii.
inline TomlKeys random_fill(int count, std::string box, const TomlKeys& changes) {
  return with({{"kind", "random"}, {"count", count}, {"box", raw(std::move(box))}, {"material", "steel"}},
              changes);
}

inline TomlKeys particle(std::initializer_list<double> position_m, const TomlKeys& changes = {}) {
  return with({{"position", position_m}, {"radius", 0.001}, {"material", "steel"}}, changes);
}

// The plane through `point_m` facing along `normal`, steel; adiabatic unless given a temperature.
inline TomlKeys plane_wall(std::initializer_list<double> point_m, std::initializer_list<double> normal,
                           const TomlKeys& changes = {}) {
  return with({{"point", point_m}, {"normal", normal}, {"material", "steel"}}, changes);
}

// The plane y = 0, facing up.
inline TomlKeys floor_wall(const TomlKeys& changes = {}) {
  return plane_wall({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, changes);
}

// [[assign]] by particle ids.
inline TomlKeys assign_ids(std::initializer_list<int> ids, const TomlKeys& changes) {
  return with({{"ids", ids}}, changes);
}

// ---- settings, for SceneBuilder::set ------------------------------------------------------

// The thermal integrator's relative and absolute tolerance (K).
inline TomlKeys tolerances(double tolerance) {
  return {{"thermal.relative_tolerance", tolerance}, {"thermal.absolute_tolerance", tolerance}};
}

// The result file and its frame interval (s).
inline TomlKeys output(const char* file, double interval_s) {
  return {{"output.file", file}, {"output.interval", interval_s}};
}

// ---- starting points ----------------------------------------------------------------------

// format, [simulation] duration = 1 s, and the steel material.
inline SceneBuilder steel_scene() {
  return SceneBuilder().set("simulation.duration", 1.0).add("material", steel());
}

// steel_scene with mechanics off and a constant 1 mW/K contact conductance: the contacts are the
// initial touching pairs, so the heat problem is linear.
inline SceneBuilder thermal_scene() {
  return steel_scene().set({{"effects.mechanics", "off"},
                            {"thermal.conductance", "constant"},
                            {"thermal.constant_conductance", 1.0e-3}});
}

}  // namespace tmdem::test
