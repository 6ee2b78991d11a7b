#pragma once
// The built-in default scene: the heated, sedimented 256-particle bed of the reference paper.
// Its text is identical to examples/paper_bed.toml (a test compares them; edit both together).
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

inline constexpr std::string_view kDefaultSceneSource = "<default scene>";

std::string_view default_scene_toml();

// load_scene_text(default_scene_toml(), "<default scene>", set_overrides).
Scene load_default_scene(const std::vector<std::string>& set_overrides = {});

}  // namespace tmdem::coupling
