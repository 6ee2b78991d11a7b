#pragma once
// Writes a TOML table as readable text: numbers in their shortest exact form (1e-06, -9.81
// rather than toml++'s 17-digit 9.9999999999999995e-07), plain values of a table first, then its
// sub-tables as [a.b] sections and its arrays of tables as [[a]] entries; tables inside an
// array-of-tables entry or an array are written inline. Reading the text back gives the same
// table. Used for Scene::resolved_toml.
#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace tmdem::coupling {

std::string write_toml(const toml::table& root);

// A text as a TOML basic string ("...", quotes, backslashes and control characters escaped): the
// scene's strings when written, and `tmdem run -o FILE` (and the Python module's
// run(output=FILE)) handed to output.file as a --set value, so that the result's resolved scene
// names the file written.
std::string toml_basic_string(std::string_view text);

// One value as inline TOML text ("1e-06", "[0.0, -9.81, 0.0]", "{ kind = \"lattice\" }").
std::string write_toml_value(const toml::node& value);

}  // namespace tmdem::coupling
