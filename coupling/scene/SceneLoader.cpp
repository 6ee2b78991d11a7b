#include "coupling/scene/SceneLoader.h"

// The parse step: TOML text (or a file) -> table -> --set overrides; then SceneBuilder builds
// and validates the Scene.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "coupling/scene/SceneBuilder.h"
#include "coupling/scene/SceneOverrides.h"
#include "coupling/scene/TomlWriter.h"

namespace tmdem::coupling {

Scene load_scene_text(std::string_view toml_text, std::string_view source_name,
                      const std::vector<std::string>& set_overrides) {
  const std::string source(source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw SceneError(source + ":" + std::to_string(begin.line) + ":" +
                     std::to_string(begin.column) +
                     ": TOML syntax error: " + std::string(error.description()));
  }
  apply_set_overrides(root, set_overrides);
  Scene scene = SceneBuilder(root, source).build();
  scene.resolved_toml = write_toml(root);
  scene.source = source;
  return scene;
}

Scene load_scene_file(const std::string& path, const std::vector<std::string>& set_overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError("cannot open scene file " + quote_text(path) + ": it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError("cannot open scene file " + quote_text(path) + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError("cannot read scene file " + quote_text(path));
  return load_scene_text(text.str(), path, set_overrides);
}

}  // namespace tmdem::coupling
