#include "coupling/scene/SceneOverrides.h"

#include <cctype>
#include <optional>
#include <sstream>
#include <string_view>

#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneSchema.h"

namespace tmdem::coupling {

namespace {

struct PathComponent {
  std::string name;
  std::optional<std::size_t> index;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool is_key_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

// "material[0].conductivity" -> {material,0}, {conductivity}; nullopt when malformed.
std::optional<std::vector<PathComponent>> parse_path(std::string_view key) {
  std::vector<PathComponent> out;
  std::size_t i = 0;
  while (true) {
    PathComponent component;
    while (i < key.size() && is_key_char(key[i])) component.name += key[i++];
    if (component.name.empty()) return std::nullopt;
    if (i < key.size() && key[i] == '[') {
      ++i;
      std::size_t index = 0;
      bool digits = false;
      while (i < key.size() && std::isdigit(static_cast<unsigned char>(key[i]))) {
        index = index * 10 + static_cast<std::size_t>(key[i++] - '0');
        digits = true;
        if (index > 1000000000) return std::nullopt;
      }
      if (!digits || i >= key.size() || key[i] != ']') return std::nullopt;
      ++i;
      component.index = index;
    }
    out.push_back(std::move(component));
    if (i == key.size()) return out;
    if (key[i] != '.') return std::nullopt;
    ++i;
  }
}

std::string toml_string_literal(std::string_view text) {
  std::ostringstream os;
  os << toml::value<std::string>(std::string(text));
  return os.str();
}

// Parses VALUE as a TOML value; the node's source is "--set KEY" for later messages.
toml::table parse_value(const std::string& key, std::string_view value, const std::string& what) {
  const std::string source = "--set " + key;
  if (value.find_first_of("\r\n") != std::string_view::npos)
    throw SceneError(what + ": the value must be on one line");
  try {
    toml::table parsed = toml::parse("x = " + std::string(value), source);
    if (parsed.size() == 1 && parsed.contains("x")) return parsed;
  } catch (const toml::parse_error& error) {
    const bool quoted_or_structured =
        !value.empty() && (value.front() == '"' || value.front() == '\'' ||
                           value.front() == '[' || value.front() == '{');
    if (value.empty() || quoted_or_structured)
      throw SceneError(what + ": the value is not a valid TOML value (" +
                       std::string(error.description()) + ")");
  }
  // A bare word (explicit, klu, out/result.h5): take it as a string.
  return toml::parse("x = " + toml_string_literal(value), source);
}

void apply_one(toml::table& root, const std::string& override_text) {
  const std::string what = "--set " + override_text;
  const auto equals = override_text.find('=');
  if (equals == std::string::npos)
    throw SceneError(what + ": expected KEY=VALUE, e.g. --set thermal.integrator=explicit");
  const std::string key(trim(std::string_view(override_text).substr(0, equals)));
  const std::string_view value = trim(std::string_view(override_text).substr(equals + 1));
  const auto path = parse_path(key);
  if (!path)
    throw SceneError(what + ": malformed key " + "\"" + key +
                     "\" (expected a dotted path such as thermal.integrator or "
                     "material[0].conductivity)");

  toml::table* current = &root;
  std::string schema;  // "" = top level
  std::string walked;  // key path so far, for messages
  for (std::size_t c = 0; c < path->size(); ++c) {
    const PathComponent& component = (*path)[c];
    const bool last = c + 1 == path->size();
    const std::string here = walked.empty() ? component.name : walked + "." + component.name;
    const SceneSchema::Key* spec = SceneSchema::find(schema, component.name);
    if (spec == nullptr) {
      std::string problem = what + ": unknown key " + here;
      const auto hint = SceneSchema::suggestion(schema, component.name);
      if (!hint.empty()) problem += " (did you mean " + std::string(hint) + "?)";
      problem += "; valid keys " + (walked.empty() ? std::string("at the top level")
                                                   : "of " + walked) +
                 ": " + SceneSchema::key_list(schema);
      throw SceneError(problem);
    }
    if (spec->kind == SceneSchema::Kind::TableArray) {
      if (!component.index)
        throw SceneError(what + ": " + here + " is an array of tables ([[" + component.name +
                         "]]); give an entry and a key, e.g. " + component.name + "[0]." +
                         std::string(SceneSchema::keys(spec->table)->front().name));
      if (last)
        throw SceneError(what + ": give a key inside " + here + "[" +
                         std::to_string(*component.index) + "], e.g. " + here + "[" +
                         std::to_string(*component.index) + "]." +
                         std::string(SceneSchema::keys(spec->table)->front().name));
      toml::array* array = current->get_as<toml::array>(component.name);
      const std::size_t size = array != nullptr ? array->size() : 0;
      const std::string indexed = here + "[" + std::to_string(*component.index) + "]";
      if (*component.index >= size)
        throw SceneError(what + ": " + indexed + " does not exist (the scene has " +
                         std::to_string(size) + " [[" + component.name + "]] entries)");
      toml::table* entry = array->get_as<toml::table>(*component.index);
      if (entry == nullptr)
        throw SceneError(what + ": " + indexed + " is not a table");
      current = entry;
      schema = std::string(spec->table);
      walked = indexed;
      continue;
    }
    if (component.index)
      throw SceneError(what + ": " + here + " is not an array of tables; remove [" +
                       std::to_string(*component.index) + "]");
    if (last) {
      toml::table parsed = parse_value(key, value, what);
      current->insert_or_assign(component.name, std::move(*parsed.get("x")));
      return;
    }
    if (spec->kind != SceneSchema::Kind::Table)
      throw SceneError(what + ": " + here + " is a value, not a table");
    toml::node* existing = current->get(component.name);
    if (existing == nullptr) {
      current->insert(component.name, toml::table{});
      existing = current->get(component.name);
    }
    toml::table* next = existing->as_table();
    if (next == nullptr) throw SceneError(what + ": " + here + " is not a table in the scene");
    current = next;
    schema = std::string(spec->table);
    walked = here;
  }
}

}  // namespace

void apply_set_overrides(toml::table& root, const std::vector<std::string>& overrides) {
  for (const auto& text : overrides) apply_one(root, text);
}

}  // namespace tmdem::coupling
