#pragma once
// The key schema of the scene file (contract section 2): which keys each table may hold and
// whether a key holds a value, a table or an array of tables. Used both to refuse unknown keys
// and to check --set KEY=VALUE paths against the schema before they are applied.
#include <string>
#include <string_view>
#include <vector>

namespace tmdem::coupling {

class SceneSchema {
 public:
  enum class Kind { Value, Table, TableArray };

  struct Key {
    constexpr Key(std::string_view key_name, Kind key_kind = Kind::Value,
                  std::string_view child_table = {})
        : name(key_name), kind(key_kind), table(child_table) {}
    std::string_view name;
    Kind kind = Kind::Value;
    std::string_view table;  // schema name of the child table (Kind::Table / Kind::TableArray)
  };

  // Schema names: "" (top level), "simulation", "effects", "material", "particle", "generate",
  // "box", "assign", "nearest", "wall", "convection", "radiation", "mechanics", "thermal",
  // "output". Returns nullptr for an unknown schema name.
  static const std::vector<Key>* keys(std::string_view schema);

  // The key `name` of `schema`, or nullptr.
  static const Key* find(std::string_view schema, std::string_view name);

  // "a, b, c": the valid keys of `schema`, in schema order.
  static std::string key_list(std::string_view schema);

  // The valid key of `schema` closest to `name` (edit distance <= 2), or "" if none is close.
  static std::string_view suggestion(std::string_view schema, std::string_view name);
};

}  // namespace tmdem::coupling
