#pragma once
// One table of a scene file, seen through the schema: typed, checked accessors whose errors are
// SceneError messages of the form
//   FILE:LINE:COLUMN: KEY.PATH: PROBLEM
// e.g. "bed.toml:14:17: material[1].young_modulus: must be > 0 (got -5)".
// A value that came from --set KEY=VALUE is located as "--set KEY" instead of FILE:LINE:COLUMN.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "coupling/scene/Scene.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::coupling {

// An allowed range of a number, with its text for messages ("must be > 0"). One type with the
// heat-transfer modes' parameter ranges, so a mode's declared range reads the same here.
using Range = thermal::ParameterRange;

// Shortest text that reads back as the same double ("0.001", "2.1e+11").
std::string format_number(double value);
// "a string", "an integer", "a floating-point number", ...
std::string describe_type(const toml::node& node);
// A TOML-style quoted string for messages.
std::string quote_text(std::string_view text);

class SceneTable {
 public:
  // table may be null (the section is absent): every optional getter then returns nothing.
  // path: key path of the table ("" top level, "thermal", "material[1]", "generate[0].box").
  // schema: SceneSchema name of the table. source: file name, the fallback location.
  // enforce_ranges: false for the section of an effect that is off (types are still checked).
  SceneTable(const toml::table* table, std::string path, std::string_view schema,
             std::string source, bool enforce_ranges = true);

  const toml::table* table() const { return table_; }
  bool present() const { return table_ != nullptr; }
  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  bool enforce_ranges() const { return enforce_; }
  std::string key_path(std::string_view key) const;

  // "FILE:LINE:COLUMN" of a node (or "--set KEY", or the bare source when unknown).
  std::string location(const toml::node* node) const;
  [[noreturn]] void fail(std::string_view key, const std::string& problem) const;
  [[noreturn]] void fail_at(const toml::node* node, const std::string& key_path,
                            const std::string& problem) const;
  [[noreturn]] void fail_here(const std::string& problem) const;  // about the table itself

  // Refuses keys that are not in the schema, naming the valid keys.
  void check_keys() const;

  bool has(std::string_view key) const { return node(key) != nullptr; }
  const toml::node* node(std::string_view key) const;

  // Numbers: integer or floating point, always finite; range checked when enforce_ranges. Without
  // a range, the schema's range of the key applies (SceneSchema::Key::range; none: any number).
  std::optional<double> optional_number(std::string_view key,
                                        std::optional<Range> range = std::nullopt) const;
  double number(std::string_view key, double fallback,
                std::optional<Range> range = std::nullopt) const;
  // The schema's default and range of the key.
  double number(std::string_view key) const;
  double required_number(std::string_view key, std::optional<Range> range = std::nullopt) const;

  // Integers in [lo, hi] (always checked: they size or index things).
  std::optional<std::int64_t> optional_integer(std::string_view key, std::int64_t lo,
                                               std::int64_t hi) const;
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi) const;
  std::int64_t required_integer(std::string_view key, std::int64_t lo, std::int64_t hi) const;

  std::optional<bool> optional_boolean(std::string_view key) const;
  bool boolean(std::string_view key, bool fallback) const;

  std::optional<std::string> optional_string(std::string_view key) const;
  std::string required_string(std::string_view key) const;
  // One of the schema's choices of the key (the message lists them); its default when absent
  // ("" for a required key: the caller reports it missing).
  std::string choice(std::string_view key) const;

  // A point or vector: 3 finite numbers, or 2 when dimension == 2 (then z = 0).
  std::optional<Vec3> optional_vec3(std::string_view key, int dimension) const;
  Vec3 required_vec3(std::string_view key, int dimension) const;

  // Non-empty arrays; elements named key[i] in messages.
  std::vector<double> required_numbers(std::string_view key, Range range = Range::any()) const;
  std::vector<std::int64_t> required_integers(std::string_view key, std::int64_t lo,
                                              std::int64_t hi) const;

  // Sub-table (schema Kind::Table) and array of tables (Kind::TableArray) of this table.
  std::optional<SceneTable> optional_table(std::string_view key, bool enforce_ranges) const;
  std::vector<SceneTable> table_array(std::string_view key, bool enforce_ranges) const;

  [[noreturn]] void missing(std::string_view key) const;

 private:
  const toml::table* table_;
  std::string path_;
  std::string schema_;
  std::string source_;
  bool enforce_;
};

}  // namespace tmdem::coupling
