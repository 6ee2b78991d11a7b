#include "PythonScene.h"

#include "coupling/scene/DefaultScene.h"
#include "coupling/scene/SceneLoader.h"

namespace py = pybind11;

namespace tmdem::python {

std::string toml_value_text(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return py::repr(value).cast<std::string>();
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    bool first = true;
    for (const py::handle item : value) {
      if (!first) text += ", ";
      first = false;
      const std::string item_text = toml_value_text(item);
      text += py::isinstance<py::str>(item) ? "\"" + item_text + "\"" : item_text;
    }
    return text + "]";
  }
  throw py::type_error("scene value must be str (TOML text), bool, int, float or a list of "
                       "them, got " + py::str(value.get_type()).cast<std::string>());
}

coupling::Scene PythonScene::reload(const std::vector<std::string>& overrides) const {
  return path_.empty() ? coupling::load_default_scene(overrides)
                       : coupling::load_scene_file(path_, overrides);
}

PythonScene PythonScene::load(const std::string& path, const std::vector<std::string>& overrides) {
  PythonScene scene;
  scene.path_ = path;
  scene.overrides_ = overrides;
  scene.scene_ = scene.reload(overrides);
  return scene;
}

PythonScene PythonScene::load_default(const std::vector<std::string>& overrides) {
  PythonScene scene;
  scene.overrides_ = overrides;
  scene.scene_ = scene.reload(overrides);
  return scene;
}

void PythonScene::set(const std::string& key, const py::handle& value) {
  std::vector<std::string> overrides = overrides_;
  overrides.push_back(key + "=" + toml_value_text(value));
  scene_ = reload(overrides);  // throws before anything changes when the override is refused
  overrides_ = std::move(overrides);
}

}  // namespace tmdem::python
