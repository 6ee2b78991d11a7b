#pragma once
// tmdem.run: the `tmdem run` code path (coupling::run_scene) for a PythonScene, with the same
// output-file choice (output=, else the scene's output.file, else tmdem-default.h5 for the
// built-in scene). Returns (summary dict, tmdem.Result of the file written); a run that does not
// end with exit code 0 raises tmdem.RunError with the exit code and the run's message.
#include <optional>
#include <string>

#include <pybind11/pybind11.h>

#include "PythonScene.h"

namespace tmdem::python {

struct RunArguments {
  std::optional<std::string> output;   // result file
  std::optional<std::string> summary;  // also write the summary JSON here
  std::optional<std::string> restart;  // continue from this checkpoint
  bool quiet = true;                   // false: progress on stderr, as `tmdem run`
  bool overwrite = false;
};

pybind11::tuple run(const PythonScene& scene, const RunArguments& arguments);

// Raised by run(); args = (message, exit_code).
struct RunFailure : std::runtime_error {
  RunFailure(const std::string& message, int code) : std::runtime_error(message), exit_code(code) {}
  int exit_code;
};

}  // namespace tmdem::python
