#pragma once
// The key schema of the scene file (contract section 2): which keys each table may hold, whether
// a key holds a value, a table or an array of tables, and for the scene reference (docs/scene.md,
// `tmdem docs scene`) its unit, default, allowed values and a one-line description. The loader
// validates with it: unknown keys, --set paths, and the range, default and choices of the keys
// that state them (SceneTable reads them from here). The sections and effects switches of the
// heat-transfer modes come from each mode's own declaration (thermal/modes/ModeRegistry.h), so a new
// mode appears here, in validation and in the docs without touching this file.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "thermal/modes/ModeDescription.h"

namespace tmdem::coupling {

class SceneSchema {
 public:
  enum class Kind { Value, Table, TableArray };

  struct Key {
    std::string name;
    Kind kind = Kind::Value;
    std::string table;  // schema name of the child table (Kind::Table / Kind::TableArray)
    std::string unit;   // "m", "W/(m^2 K)"; "" for a pure number or a non-number
    // Default as TOML text ("0.5", "\"cvode\"", "[0, 0, 0]"); "" with required: must be given;
    // "" otherwise: absent means nothing (e.g. an adiabatic wall).
    std::string default_text;
    bool required = false;
    std::string allowed;      // allowed values in words, for the reference
    std::string description;  // one line
    // Set for numbers the schema checks itself: SceneTable uses this range and default when the
    // loader gives none.
    std::optional<thermal::ParameterRange> range;
    std::optional<double> default_number;
    std::vector<std::string> choices;  // set for strings with a fixed set of values
  };

  struct Section {
    std::string name;         // schema name: "", "simulation", "material", "convection", ...
    std::string description;  // one line
    std::vector<Key> keys;
  };

  // Schema names: "" (top level), "simulation", "effects", "material", "particle", "generate",
  // "box", "assign", "nearest", "wall", one per heat-transfer mode section ("convection",
  // "radiation", ...), "mechanics", "thermal", "output". Returns nullptr for an unknown name.
  static const std::vector<Key>* keys(std::string_view schema);

  // Every section, in file order (the order of the reference).
  static const std::vector<Section>& sections();

  // The key `name` of `schema`, or nullptr.
  static const Key* find(std::string_view schema, std::string_view name);

  // "a, b, c": the valid keys of `schema`, in schema order.
  static std::string key_list(std::string_view schema);

  // The valid key of `schema` closest to `name` (edit distance <= 2), or "" if none is close.
  static std::string_view suggestion(std::string_view schema, std::string_view name);
};

// A plain value key (no range, no choices): what every schema table builds its free-form keys
// from (SceneSchema.cpp's tables, the probe table of SceneProbes.cpp).
SceneSchema::Key schema_value_key(std::string name, std::string unit, std::string default_text,
                                  std::string allowed, std::string description, bool required = false);

}  // namespace tmdem::coupling
