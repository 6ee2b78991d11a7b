#pragma once
// tmdem.Scene: a scene file (or the built-in default scene) plus the --set overrides applied to
// it so far. Every set() reloads through the same loader as `tmdem run --set`, so a bad key or
// value is refused at once with the loader's message (SceneError naming the key).
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "coupling/scene/Scene.h"

namespace tmdem::python {

class PythonScene {
 public:
  static PythonScene load(const std::string& path, const std::vector<std::string>& overrides);
  static PythonScene load_default(const std::vector<std::string>& overrides);

  // KEY=VALUE exactly as --set; VALUE is TOML text (str) or a Python bool/int/float/list.
  void set(const std::string& key, const pybind11::handle& value);

  const coupling::Scene& scene() const { return scene_; }
  const std::string& path() const { return path_; }  // empty: the built-in scene
  const std::vector<std::string>& overrides() const { return overrides_; }

 private:
  coupling::Scene reload(const std::vector<std::string>& overrides) const;

  std::string path_;
  std::vector<std::string> overrides_;
  coupling::Scene scene_;
};

// A Python value as the TOML text --set takes: True -> "true", 1e-3 -> "0.001" (shortest
// round-trip repr, so the double is exactly the one given), [1, 2.5] -> "[1, 2.5]"; a str is
// passed on as it is. TypeError for anything else.
std::string toml_value_text(const pybind11::handle& value);

}  // namespace tmdem::python
