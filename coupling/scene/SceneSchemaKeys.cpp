// The builders of the scene schema's keys (SceneSchemaKeys.h), moved out of SceneSchema.cpp.
#include "coupling/scene/SceneSchemaKeys.h"

#include "mechanics/solvers/ContactSolverRegistry.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling::schema_keys {

Key table(std::string name, Kind kind, std::string description, bool required) {
  Key k;
  k.table = name;
  k.name = std::move(name);
  k.kind = kind;
  k.required = required;
  k.description = std::move(description);
  return k;
}

// A number the schema checks itself: range and default (none: required, or absent = unset).
Key number(std::string name, std::string unit, std::optional<double> fallback, Range range,
           std::string description, bool required) {
  Key k;
  k.name = std::move(name);
  k.unit = std::move(unit);
  k.range = range;
  k.default_number = fallback;
  if (fallback) k.default_text = thermal::parameter_text(*fallback);
  k.required = required;
  k.allowed = range.interval();
  k.description = std::move(description);
  return k;
}

Key required_number(std::string name, std::string unit, Range range, std::string description) {
  return number(std::move(name), std::move(unit), std::nullopt, range, std::move(description), true);
}

Key value(std::string name, std::string unit, std::string default_text, std::string allowed,
          std::string description, bool required) {
  return schema_value_key(std::move(name), std::move(unit), std::move(default_text),
                          std::move(allowed), std::move(description), required);
}

Key boolean(std::string name, std::string default_text, std::string description) {
  return value(std::move(name), "", std::move(default_text), "true, false", std::move(description));
}

std::string bool_text(bool value) { return value ? "true" : "false"; }

// A registry's names as the schema's strings.
std::vector<std::string> names_of(const std::vector<std::string_view>& names) {
  return {names.begin(), names.end()};
}

// thermal.linear_solver: "auto" (resolved by the run, never a solver itself) and the solvers.
std::vector<std::string> linear_solver_choices() {
  auto names = names_of(thermal::linear_solver_names());
  names.insert(names.begin(), std::string(thermal::kAutoLinearSolverName));
  return names;
}

Key choice(std::string name, std::string fallback, const std::vector<std::string>& choices,
           std::string description) {
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here.
  std::string quoted;
  if (!fallback.empty()) {
    quoted += '"';
    quoted += fallback;
    quoted += '"';
  }
  Key k = value(std::move(name), "", quoted, "", std::move(description), fallback.empty());
  for (const auto& c : choices) {
    if (!k.allowed.empty()) k.allowed += ", ";
    k.allowed += '"';
    k.allowed += c;
    k.allowed += '"';
    k.choices.push_back(c);
  }
  return k;
}

Key vector3(std::string name, std::string unit, std::string default_text, std::string description,
            bool required) {
  return value(std::move(name), std::move(unit), std::move(default_text),
               "3 finite numbers (2 in 2D, z = 0)", std::move(description), required);
}

Key material_reference() {
  return value("material", "", "", "a [[material]] name", "material of the body", true);
}

// temperature, fixed_temperature, heat_source, fixed: what [[particle]], [[generate]] and
// [[assign]] may set on particles. New particles start at Particle's defaults (Scene.h: 293.15 K,
// not held, without a source, free to move); [[assign]] changes only what it gives.
std::vector<Key> particle_settings(bool new_particles) {
  std::vector<Key> keys{
      number("temperature", "K", std::nullopt, Range::greater(0.0), "initial temperature"),
      boolean("fixed_temperature", "", "held at its temperature for the whole run"),
      number("heat_source", "W", std::nullopt, Range::any(), "imposed power"),
      boolean("fixed", "", "does not move")};
  if (new_particles) {  // Particle's defaults (Scene.h)
    const Particle fresh;
    const std::string defaults[4] = {thermal::parameter_text(fresh.temperature_K),
                                     fresh.fixed_temperature ? "true" : "false",
                                     thermal::parameter_text(fresh.heat_source_W),
                                     fresh.fixed ? "true" : "false"};
    for (std::size_t i = 0; i < 4; ++i) keys[i].default_text = defaults[i];
  }
  return keys;
}

std::vector<Key> concat(std::vector<Key> a, const std::vector<Key>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace tmdem::coupling::schema_keys
