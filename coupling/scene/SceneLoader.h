#pragma once
// Scene loading and validation (contract section 2): TOML text -> --set overrides -> checked,
// generated, assigned Scene (parse: SceneLoader.cpp; build: SceneBuilder; validate:
// SceneValidation, SceneLimits). Every problem is a SceneError (exit code 2) whose message names
// what is wrong:
//   TOML syntax         "bed.toml:12:7: TOML syntax error: <description>"
//   bad value           "bed.toml:14:17: material[1].young_modulus: must be > 0 (got -5)"
//   wrong type          "bed.toml:3:12: simulation.duration: expected a number, got a string"
//   missing key         "bed.toml:1:1: simulation.duration: required key is missing"
//   unknown key         "bed.toml:20:1: thermal.integratr: unknown key (did you mean integrator?);
//                        valid keys here: integrator, linear_solver, ..."
//   choice              "bed.toml:21:14: thermal.integrator: must be one of "cvode", "ida",
//                        "explicit" (got "rk4")"
//   overlap             "bed.toml: particles 3 and 17 overlap at start: ..."
//   missing file        "cannot open scene file "bed.toml": No such file or directory"
//   --set               "--set thermal.integratr=ida: unknown key thermal.integratr ..."
// A bad value that came from --set is located as "--set KEY" instead of FILE:LINE:COLUMN.
//
// Rules beyond the contract text (all documented in the messages too):
// - [[material]]: name, density, young_modulus, poisson_ratio, conductivity, heat_capacity are
//   required; friction defaults to 0.3, emissivity to 0.0. Names must be unique.
// - [[particle]]: position, radius, material required; temperature defaults to 293.15 K; also
//   accepts fixed_temperature, heat_source and fixed like [[assign]].
// - [[generate]]: material required; temperature (default 293.15 K), fixed_temperature,
//   heat_source, fixed accepted for every kind; a key that belongs to another kind (rows with
//   kind = "column") is an error. Geometry: coupling/SceneGenerators.h. "random" uses
//   place_random with seed simulation.seed + (index of the [[generate]] entry);
//   particles lie entirely inside the box (2D: z = middle of the box's z range).
// - [[assign]]: exactly one of ids, box (centre inside, inclusive), nearest (centre distance,
//   ties by id); at least one of temperature, fixed_temperature, heat_source, fixed,
//   material; a box that selects nothing is an error. In 2D, box and nearest ignore z.
// - Vectors have 3 components, or 2 in 2D (z = 0). In 2D gravity z must be 0 and a lattice's
//   nz must be 1.
// - Every key's range, default and choices: docs/scene.md (generated from SceneSchema, the
//   heat-transfer modes' sections from each mode's own declaration). Temperatures > 0 K;
//   max_iterations >= 1; settle_time, settle_velocity, constant_conductance > 0;
//   checkpoint_interval >= 0; output.file non-empty.
// - effects.mechanics = "off" with conductance = "hertz" is an error when conduction is on.
// - Range checks of a heat-transfer mode's section (and its own check) and of [mechanics] apply
//   only when their effect is on; unknown keys and types are checked always.
// - Particles overlapping each other (mechanics::find_overlaps) or a wall at start
//   (gap < -1e-9 r) are errors naming the particle ids (and wall index). A scene needs at
//   least one particle.
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/Scene.h"
#include "coupling/scene/SceneError.h"

namespace tmdem::coupling {

// set_overrides: the --set KEY=VALUE strings, applied in order before validation (see
// coupling/SceneOverrides.h). Scene::resolved_toml is the table after the overrides;
// Scene::source is `path` / `source_name`.
Scene load_scene_file(const std::string& path, const std::vector<std::string>& set_overrides = {});
Scene load_scene_text(std::string_view toml_text, std::string_view source_name,
                      const std::vector<std::string>& set_overrides = {});

}  // namespace tmdem::coupling
