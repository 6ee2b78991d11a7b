// The `tmdem` Python module: scenes (load, --set), runs (the `tmdem run` code path) and result
// files as NumPy arrays. Errors keep the program's messages: SceneError (a ValueError) names
// the bad key or value, OutputError (an OSError) the file, RunError carries the exit code.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "PythonProbes.h"
#include "PythonResult.h"
#include "PythonRun.h"
#include "PythonScene.h"
#include "coupling/output/OutputError.h"
#include "coupling/scene/SceneError.h"

namespace py = pybind11;
using tmdem::python::PythonResult;
using tmdem::python::PythonScene;

PYBIND11_MODULE(tmdem, m) {
  m.doc() = "tmdem: heat flow through granular packings (scenes, runs, result files)";
  m.attr("__version__") = TMDEM_VERSION;

  static py::exception<tmdem::coupling::SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  static py::exception<tmdem::coupling::OutputError> output_error(m, "OutputError", PyExc_OSError);
  static py::exception<tmdem::python::RunFailure> run_error(m, "RunError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tmdem::coupling::SceneError& e) {
      PyErr_SetString(scene_error.ptr(), e.what());
    } catch (const tmdem::coupling::OutputError& e) {
      PyErr_SetString(output_error.ptr(), e.what());
    } catch (const tmdem::python::RunFailure& e) {
      py::object error = py::handle(run_error.ptr())(e.what(), e.exit_code);
      PyErr_SetObject(run_error.ptr(), error.ptr());
    }
  });

  py::class_<PythonScene>(m, "Scene", "a scene with its --set overrides, validated")
      .def_static("load", &PythonScene::load, py::arg("path"),
                  py::arg("set") = std::vector<std::string>{},
                  "read a scene file (TOML); set: KEY=VALUE strings as --set")
      .def_static("default", &PythonScene::load_default,
                  py::arg("set") = std::vector<std::string>{}, "the built-in paper bed")
      .def("set", &PythonScene::set, py::arg("key"), py::arg("value"),
           "change one key as --set KEY=VALUE; value: TOML text, bool, int, float or list")
      .def_property_readonly("path", &PythonScene::path)
      .def_property_readonly("overrides", &PythonScene::overrides)
      .def_property_readonly("source", [](const PythonScene& s) { return s.scene().source; })
      .def_property_readonly("toml", [](const PythonScene& s) { return s.scene().resolved_toml; },
                             "the scene as TOML text after the overrides")
      .def_property_readonly("particles",
                             [](const PythonScene& s) { return s.scene().particles.size(); })
      .def_property_readonly("duration", [](const PythonScene& s) { return s.scene().duration_s; })
      .def_property_readonly("output_file",
                             [](const PythonScene& s) { return s.scene().output.file; })
      .def("__repr__", [](const PythonScene& s) {
        return "<tmdem.Scene " + s.scene().source + ", " +
               std::to_string(s.scene().particles.size()) + " particles, " +
               std::to_string(s.overrides().size()) + " overrides>";
      });

  m.def(
      "run",
      [](const PythonScene& scene, std::optional<std::string> output,
         std::optional<std::string> summary, bool quiet, bool overwrite,
         std::optional<std::string> restart) {
        return tmdem::python::run(scene, {output, summary, restart, quiet, overwrite});
      },
      py::arg("scene"), py::arg("output") = py::none(), py::arg("summary") = py::none(),
      py::arg("quiet") = true, py::arg("overwrite") = false, py::arg("restart") = py::none(),
      "run the scene as `tmdem run`; returns (summary dict, Result)");

  m.def("read_probes", &tmdem::python::read_probes, py::arg("path"),
        "the [[probe]] readings of a result file: dict name -> dict of arrays time_s, count, "
        "mean_K, min_K, max_K (count 0: no particle inside, temperatures 0); {} without probes");

  py::class_<PythonResult>(m, "Result", "a result file read into NumPy arrays")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def_readonly("path", &PythonResult::path)
      .def_readonly("format", &PythonResult::format)
      .def_readonly("status", &PythonResult::status)
      .def_readonly("scene", &PythonResult::scene)
      .def_readonly("contacts_stored", &PythonResult::contacts_stored)
      .def_readonly("radius", &PythonResult::radius)
      .def_readonly("mass", &PythonResult::mass)
      .def_readonly("heat_capacity", &PythonResult::heat_capacity)
      .def_readonly("material", &PythonResult::material)
      .def_readonly("times", &PythonResult::time)
      .def_readonly("thermal_energy", &PythonResult::thermal_energy)
      .def_readonly("boundary_heat", &PythonResult::boundary_heat)
      .def_readonly("position", &PythonResult::position)
      .def_readonly("velocity", &PythonResult::velocity)
      .def_readonly("temperature", &PythonResult::temperature)
      .def_readonly("contact_offset", &PythonResult::contact_offset)
      .def_readonly("pair", &PythonResult::pair)
      .def_readonly("normal_force", &PythonResult::normal_force)
      .def_readonly("tangential_force", &PythonResult::tangential_force)
      .def_readonly("conductance", &PythonResult::conductance)
      .def_readonly("heat_flow", &PythonResult::heat_flow)
      .def_property_readonly("frames", &PythonResult::frames)
      .def("contacts", &PythonResult::contacts, py::arg("frame"),
           "frame's contacts: dict of pair, normal_force, tangential_force, conductance, heat_flow")
      .def("__repr__", [](const PythonResult& r) {
        return "<tmdem.Result " + r.path + ", " + std::to_string(r.frames()) + " frames, " +
               std::to_string(r.radius.shape(0)) + " particles, status " + r.status + ">";
      });
}
