#include "coupling/scene/SceneTable.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "coupling/common/ShortestNumber.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneSchema.h"

namespace tmdem::coupling {

std::string format_number(double value) { return shortest_number(value); }

std::string describe_type(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "nothing";
  }
}

std::string quote_text(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
  return out;
}

namespace {

// Short text of a value for "(got ...)".
std::string describe_value(const toml::node& node) {
  if (const auto* s = node.as_string()) return quote_text(s->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) return format_number(f->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  return describe_type(node);
}

Range schema_range(std::string_view schema, std::string_view key) {
  const auto* spec = SceneSchema::find(schema, key);
  return spec != nullptr && spec->range ? *spec->range : Range::any();
}

std::optional<double> as_number(const toml::node& node) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) return f->get();
  return std::nullopt;
}

}  // namespace

SceneTable::SceneTable(const toml::table* table, std::string path, std::string_view schema,
                       std::string source, bool enforce_ranges)
    : table_(table),
      path_(std::move(path)),
      schema_(schema),
      source_(std::move(source)),
      enforce_(enforce_ranges) {}

std::string SceneTable::key_path(std::string_view key) const {
  if (path_.empty()) return std::string(key);
  return path_ + "." + std::string(key);
}

std::string SceneTable::location(const toml::node* node) const {
  if (node != nullptr) {
    const auto& region = node->source();
    if (region.path && !region.path->empty()) {
      if (region.path->starts_with("--set ")) return *region.path;
      if (region.begin)
        return *region.path + ":" + std::to_string(region.begin.line) + ":" +
               std::to_string(region.begin.column);
    }
  }
  return source_;
}

void SceneTable::fail_at(const toml::node* node, const std::string& key_path,
                         const std::string& problem) const {
  const toml::node* where = node != nullptr ? node : table_;
  throw SceneError(location(where) + ": " + key_path + ": " + problem);
}

void SceneTable::fail(std::string_view key, const std::string& problem) const {
  fail_at(node(key), key_path(key), problem);
}

void SceneTable::fail_here(const std::string& problem) const {
  throw SceneError(location(table_) + ": " + (path_.empty() ? "scene" : path_) + ": " + problem);
}

void SceneTable::missing(std::string_view key) const {
  fail_at(table_, key_path(key), "required key is missing");
}

const toml::node* SceneTable::node(std::string_view key) const {
  if (table_ == nullptr) return nullptr;
  return table_->get(key);
}

void SceneTable::check_keys() const {
  if (table_ == nullptr) return;
  for (const auto& [key, value] : *table_) {
    if (SceneSchema::find(schema_, key.str()) != nullptr) continue;
    std::string problem = "unknown key";
    const auto hint = SceneSchema::suggestion(schema_, key.str());
    if (!hint.empty()) problem += " (did you mean " + std::string(hint) + "?)";
    problem += "; valid keys here: " + SceneSchema::key_list(schema_);
    fail_at(&value, key_path(key.str()), problem);
  }
}

std::optional<double> SceneTable::optional_number(std::string_view key,
                                                  std::optional<Range> given) const {
  const Range range = given ? *given : schema_range(schema_, key);
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto value = as_number(*n);
  if (!value) fail(key, "expected a number, got " + describe_type(*n));
  if (!std::isfinite(*value)) fail(key, "must be a finite number (got " + format_number(*value) + ")");
  if (enforce_ && !range.contains(*value))
    fail(key, range.describe() + " (got " + describe_value(*n) + ")");
  return value;
}

double SceneTable::number(std::string_view key, double fallback, std::optional<Range> range) const {
  return optional_number(key, range).value_or(fallback);
}

double SceneTable::number(std::string_view key) const {
  const auto* spec = SceneSchema::find(schema_, key);
  if (spec == nullptr || !spec->default_number)
    throw std::logic_error("scene schema: " + key_path(key) + " has no default number");
  return number(key, *spec->default_number);
}

double SceneTable::required_number(std::string_view key, std::optional<Range> range) const {
  const auto value = optional_number(key, range);
  if (!value) missing(key);
  return *value;
}

std::optional<std::int64_t> SceneTable::optional_integer(std::string_view key, std::int64_t lo,
                                                         std::int64_t hi) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* i = n->as_integer();
  if (i == nullptr) fail(key, "expected an integer, got " + describe_type(*n));
  const std::int64_t v = i->get();
  if (v < lo || v > hi) {
    std::string allowed;
    if (hi == std::numeric_limits<std::int64_t>::max() || hi == std::numeric_limits<int>::max())
      allowed = "must be an integer >= " + std::to_string(lo);
    else if (hi == lo + 1)
      allowed = "must be " + std::to_string(lo) + " or " + std::to_string(hi);
    else
      allowed = "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    fail(key, allowed + " (got " + std::to_string(v) + ")");
  }
  return v;
}

std::int64_t SceneTable::integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                                 std::int64_t hi) const {
  return optional_integer(key, lo, hi).value_or(fallback);
}

std::int64_t SceneTable::required_integer(std::string_view key, std::int64_t lo,
                                          std::int64_t hi) const {
  const auto value = optional_integer(key, lo, hi);
  if (!value) missing(key);
  return *value;
}

std::optional<bool> SceneTable::optional_boolean(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* b = n->as_boolean();
  if (b == nullptr) fail(key, "expected a boolean (true or false), got " + describe_type(*n));
  return b->get();
}

bool SceneTable::boolean(std::string_view key, bool fallback) const {
  return optional_boolean(key).value_or(fallback);
}

std::optional<std::string> SceneTable::optional_string(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* s = n->as_string();
  if (s == nullptr) fail(key, "expected a string, got " + describe_type(*n));
  return s->get();
}

std::string SceneTable::required_string(std::string_view key) const {
  auto value = optional_string(key);
  if (!value) missing(key);
  return *value;
}

std::string SceneTable::choice(std::string_view key) const {
  const auto* spec = SceneSchema::find(schema_, key);
  if (spec == nullptr || spec->choices.empty())
    throw std::logic_error("scene schema: " + key_path(key) + " has no choices");
  const auto value = optional_string(key);
  if (!value) {
    // default_text is TOML text: "\"cvode\"" -> cvode.
    const std::string& fallback = spec->default_text;
    return fallback.size() >= 2 ? fallback.substr(1, fallback.size() - 2) : std::string();
  }
  for (const auto& c : spec->choices)
    if (*value == c) return *value;
  std::string allowed;
  for (const auto& c : spec->choices) allowed += (allowed.empty() ? "" : ", ") + quote_text(c);
  fail(key, "must be one of " + allowed + " (got " + quote_text(*value) + ")");
}

std::optional<Vec3> SceneTable::optional_vec3(std::string_view key, int dimension) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const std::string expected =
      dimension == 2 ? "expected an array of 3 numbers (or 2 in 2D: [x, y])"
                     : "expected an array of 3 numbers [x, y, z]";
  const auto* array = n->as_array();
  if (array == nullptr) fail(key, expected + ", got " + describe_type(*n));
  const std::size_t size = array->size();
  if (size != 3 && !(dimension == 2 && size == 2))
    fail(key, expected + ", got " + std::to_string(size) + " elements");
  Vec3 out{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < size; ++i) {
    const toml::node& element = *array->get(i);
    const std::string element_path = key_path(key) + "[" + std::to_string(i) + "]";
    const auto value = as_number(element);
    if (!value) fail_at(&element, element_path, "expected a number, got " + describe_type(element));
    if (!std::isfinite(*value))
      fail_at(&element, element_path,
              "must be a finite number (got " + format_number(*value) + ")");
    out[i] = *value;
  }
  return out;
}

Vec3 SceneTable::required_vec3(std::string_view key, int dimension) const {
  const auto value = optional_vec3(key, dimension);
  if (!value) missing(key);
  return *value;
}

std::vector<double> SceneTable::required_numbers(std::string_view key, Range range) const {
  const toml::node* n = node(key);
  if (n == nullptr) missing(key);
  const auto* array = n->as_array();
  if (array == nullptr) fail(key, "expected an array of numbers, got " + describe_type(*n));
  if (array->empty()) fail(key, "must not be empty");
  std::vector<double> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string element_path = key_path(key) + "[" + std::to_string(i) + "]";
    const auto value = as_number(element);
    if (!value) fail_at(&element, element_path, "expected a number, got " + describe_type(element));
    if (!std::isfinite(*value))
      fail_at(&element, element_path,
              "must be a finite number (got " + format_number(*value) + ")");
    if (enforce_ && !range.contains(*value))
      fail_at(&element, element_path, range.describe() + " (got " + describe_value(element) + ")");
    out.push_back(*value);
  }
  return out;
}

std::vector<std::int64_t> SceneTable::required_integers(std::string_view key, std::int64_t lo,
                                                        std::int64_t hi) const {
  const toml::node* n = node(key);
  if (n == nullptr) missing(key);
  const auto* array = n->as_array();
  if (array == nullptr) fail(key, "expected an array of integers, got " + describe_type(*n));
  if (array->empty()) fail(key, "must not be empty");
  std::vector<std::int64_t> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string element_path = key_path(key) + "[" + std::to_string(i) + "]";
    const auto* value = element.as_integer();
    if (value == nullptr)
      fail_at(&element, element_path, "expected an integer, got " + describe_type(element));
    if (value->get() < lo || value->get() > hi) {
      const std::string allowed =
          hi == std::numeric_limits<std::int64_t>::max()
              ? "must be >= " + std::to_string(lo)
              : "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
      fail_at(&element, element_path, allowed + " (got " + std::to_string(value->get()) + ")");
    }
    out.push_back(value->get());
  }
  return out;
}

std::optional<SceneTable> SceneTable::optional_table(std::string_view key,
                                                     bool enforce_ranges) const {
  const auto* spec = SceneSchema::find(schema_, key);
  const std::string child_schema = spec != nullptr ? std::string(spec->table) : std::string(key);
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* t = n->as_table();
  if (t == nullptr) fail(key, "expected a table, got " + describe_type(*n));
  SceneTable child(t, key_path(key), child_schema, source_, enforce_ranges);
  child.check_keys();
  return child;
}

std::vector<SceneTable> SceneTable::table_array(std::string_view key, bool enforce_ranges) const {
  const auto* spec = SceneSchema::find(schema_, key);
  const std::string child_schema = spec != nullptr ? std::string(spec->table) : std::string(key);
  std::vector<SceneTable> out;
  const toml::node* n = node(key);
  if (n == nullptr) return out;
  const auto* array = n->as_array();
  const std::string expected = "expected an array of tables ([[" + std::string(key) + "]])";
  if (array == nullptr) fail(key, expected + ", got " + describe_type(*n));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string element_path = key_path(key) + "[" + std::to_string(i) + "]";
    const auto* t = element.as_table();
    if (t == nullptr) fail_at(&element, element_path, expected + ", got " + describe_type(element));
    SceneTable child(t, element_path, child_schema, source_, enforce_ranges);
    child.check_keys();
    out.push_back(std::move(child));
  }
  return out;
}

}  // namespace tmdem::coupling
