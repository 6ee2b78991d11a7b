#include "coupling/scene/SceneSchema.h"

#include <algorithm>
#include <map>

namespace tmdem::coupling {

namespace {

using Kind = SceneSchema::Kind;
using Key = SceneSchema::Key;

const std::map<std::string_view, std::vector<Key>>& schema_map() {
  static const std::map<std::string_view, std::vector<Key>> schema = {
      {"",
       {{"format"},
        {"simulation", Kind::Table, "simulation"},
        {"effects", Kind::Table, "effects"},
        {"material", Kind::TableArray, "material"},
        {"particle", Kind::TableArray, "particle"},
        {"generate", Kind::TableArray, "generate"},
        {"assign", Kind::TableArray, "assign"},
        {"wall", Kind::TableArray, "wall"},
        {"convection", Kind::Table, "convection"},
        {"radiation", Kind::Table, "radiation"},
        {"mechanics", Kind::Table, "mechanics"},
        {"thermal", Kind::Table, "thermal"},
        {"output", Kind::Table, "output"}}},
      {"simulation", {{"duration"}, {"dimension"}, {"gravity"}, {"seed"}}},
      {"effects", {{"mechanics"}, {"conduction"}, {"convection"}, {"radiation"}}},
      {"material",
       {{"name"},
        {"density"},
        {"young_modulus"},
        {"poisson_ratio"},
        {"friction"},
        {"conductivity"},
        {"heat_capacity"},
        {"emissivity"}}},
      {"particle",
       {{"position"},
        {"radius"},
        {"material"},
        {"temperature"},
        {"fixed_temperature"},
        {"heat_source"},
        {"fixed"}}},
      {"generate",
       {{"kind"},
        {"rows"},
        {"count"},
        {"counts"},
        {"spacing"},
        {"radius"},
        {"radii"},
        {"fractions"},
        {"origin"},
        {"box", Kind::Table, "box"},
        {"material"},
        {"temperature"},
        {"fixed_temperature"},
        {"heat_source"},
        {"fixed"}}},
      {"box", {{"min"}, {"max"}}},
      {"assign",
       {{"ids"},
        {"box", Kind::Table, "box"},
        {"nearest", Kind::Table, "nearest"},
        {"temperature"},
        {"fixed_temperature"},
        {"heat_source"},
        {"fixed"},
        {"material"}}},
      {"nearest", {{"point"}, {"count"}}},
      {"wall", {{"point"}, {"normal"}, {"material"}, {"temperature"}}},
      {"convection", {{"coefficient"}, {"fluid_temperature"}}},
      {"radiation", {{"ambient_temperature"}}},
      {"mechanics",
       {{"time_step"},
        {"theta"},
        {"solver"},
        {"tolerance"},
        {"max_iterations"},
        {"settle_time"},
        {"settle_velocity"}}},
      {"thermal",
       {{"integrator"},
        {"linear_solver"},
        {"relative_tolerance"},
        {"absolute_tolerance"},
        {"explicit_step"},
        {"conductance"},
        {"constant_conductance"},
        {"coupling"}}},
      {"output", {{"file"}, {"interval"}, {"contacts"}, {"checkpoint_interval"}}},
  };
  return schema;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

const std::vector<Key>* SceneSchema::keys(std::string_view schema) {
  const auto& map = schema_map();
  const auto it = map.find(schema);
  return it == map.end() ? nullptr : &it->second;
}

const Key* SceneSchema::find(std::string_view schema, std::string_view name) {
  const auto* list = keys(schema);
  if (list == nullptr) return nullptr;
  for (const auto& key : *list)
    if (key.name == name) return &key;
  return nullptr;
}

std::string SceneSchema::key_list(std::string_view schema) {
  std::string out;
  if (const auto* list = keys(schema)) {
    for (const auto& key : *list) {
      if (!out.empty()) out += ", ";
      out += key.name;
    }
  }
  return out;
}

std::string_view SceneSchema::suggestion(std::string_view schema, std::string_view name) {
  std::string_view best;
  std::size_t best_distance = 3;
  if (const auto* list = keys(schema)) {
    for (const auto& key : *list) {
      const std::size_t d = edit_distance(name, key.name);
      if (d < best_distance) {
        best_distance = d;
        best = key.name;
      }
    }
  }
  return best;
}

}  // namespace tmdem::coupling
