#pragma once
// The scene reference (docs/scene.md, `tmdem docs scene`): every key of the scene file with its
// unit, default, allowed values and a one-line description, generated from SceneSchema, the same
// schema the loader validates with, the heat-transfer modes' own sections included.
#include <string>

namespace tmdem::coupling {

// The reference as Markdown.
std::string scene_reference_markdown();

}  // namespace tmdem::coupling
