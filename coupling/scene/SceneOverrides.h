#pragma once
// --set KEY=VALUE overrides, applied to the parsed scene table before validation.
//
// KEY is a dotted path checked against the scene schema: "thermal.integrator",
// "simulation.duration", "format", and entries of arrays of tables by index:
// "material[0].conductivity", "generate[1].box.min". Missing sections ([thermal], a box table)
// are created; an indexed entry must exist in the scene. VALUE is parsed as a TOML value
// ("10", "1e-3", "true", "[0, -9.81, 0]", "\"klu\""); a value that is not valid TOML and does
// not start with a quote, [ or { is taken as a string, so --set thermal.integrator=explicit works.
// Errors (SceneError) name the override: "--set thermal.integratr=...: unknown key ...".
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace tmdem::coupling {

void apply_set_overrides(toml::table& root, const std::vector<std::string>& overrides);

}  // namespace tmdem::coupling
