#pragma once
// The builders of the scene schema's keys (SceneSchema.h), shared by the files that declare its
// sections: SceneSchema.cpp (the scene's bodies and the top level) and SceneSchemaSettings.cpp
// (the [mechanics], [thermal] and [output] settings).
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/SceneSchema.h"
#include "coupling/scene/Scene.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::coupling::schema_keys {

using Kind = SceneSchema::Kind;
using Key = SceneSchema::Key;
using Section = SceneSchema::Section;
using Range = thermal::ParameterRange;
// The defaults the settings keys state: Scene.h's structs, where each is written once.
inline const MechanicsSettings kMechanicsDefaults{};
inline const ThermalSettings kThermalDefaults{};
inline const OutputSettings kOutputDefaults{};

// A table or array of tables.
Key table(std::string name, Kind kind, std::string description, bool required = false);
// A number the schema checks itself: range and default (none: required, or absent = unset).
Key number(std::string name, std::string unit, std::optional<double> fallback, Range range,
           std::string description, bool required = false);
Key required_number(std::string name, std::string unit, Range range, std::string description);
// A value described in words (its checks are the loader's).
Key value(std::string name, std::string unit, std::string default_text, std::string allowed,
          std::string description, bool required = false);
Key boolean(std::string name, std::string default_text, std::string description);
std::string bool_text(bool value);  // "true", "false": a boolean default as TOML text
std::vector<std::string> names_of(const std::vector<std::string_view>& names);
template <std::size_t N>
std::vector<std::string> names_of(const std::array<std::string_view, N>& names) {
  return {names.begin(), names.end()};
}
std::vector<std::string> linear_solver_choices();
// One of `choices`, `fallback` its default (empty: none).
Key choice(std::string name, std::string fallback, const std::vector<std::string>& choices,
           std::string description);
Key vector3(std::string name, std::string unit, std::string default_text, std::string description,
            bool required = true);
Key material_reference();
// The per-particle settings of [[particle]], [[generate]] and [[import]].
std::vector<Key> particle_settings(bool new_particles);
std::vector<Key> concat(std::vector<Key> a, const std::vector<Key>& b);

// The [mechanics], [thermal] and [output] sections, in that order (SceneSchemaSettings.cpp).
std::vector<Section> settings_sections();

}  // namespace tmdem::coupling::schema_keys
