#include "PythonRun.h"

#include <unistd.h>

#include <iostream>
#include <optional>
#include <sstream>

#include "PythonResult.h"
#include "coupling/scene/TomlWriter.h"
#include "coupling/run/CoupledRun.h"

namespace py = pybind11;

namespace tmdem::python {

py::tuple run(const PythonScene& scene, const RunArguments& arguments) {
  // output= overrides output.file, as -o does: the result's resolved scene names the file.
  std::optional<PythonScene> with_output;
  if (arguments.output) {
    auto overrides = scene.overrides();
    overrides.push_back("output.file=" + coupling::toml_basic_string(*arguments.output));
    with_output = scene.path().empty() ? PythonScene::load_default(overrides)
                                       : PythonScene::load(scene.path(), overrides);
  }
  const coupling::Scene& s = with_output ? with_output->scene() : scene.scene();
  coupling::RunOptions options;
  options.output_path = arguments.output ? *arguments.output
                        : scene.path().empty() && s.output.file.empty() ? "tmdem-default.h5"
                                                                        : s.output.file;
  options.summary_path = arguments.summary.value_or("");
  options.restart_path = arguments.restart.value_or("");
  options.scene_path = scene.path();
  options.overwrite = arguments.overwrite;
  options.quiet = arguments.quiet;
  options.terminal = !arguments.quiet && isatty(STDERR_FILENO);
  // Python owns SIGINT; the resume hint names the equivalent command line.
  options.handle_signals = false;
  options.resume_command = "tmdem run" + (scene.path().empty() ? "" : " " + scene.path());
  for (const auto& set : scene.overrides()) options.resume_command += " --set '" + set + "'";
  options.resume_command += " -o " + options.output_path;

  std::ostringstream quiet_log;
  std::ostream& log = arguments.quiet ? static_cast<std::ostream&>(quiet_log) : std::cerr;
  coupling::RunOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = coupling::run_scene(s, options, log);
  }
  if (outcome.exit_code != 0) {
    std::string message = outcome.summary.message.empty() ? quiet_log.str() : outcome.summary.message;
    throw RunFailure("run of " + s.source + " ended with exit code " +
                         std::to_string(outcome.exit_code) + " (status " + outcome.summary.status +
                         "): " + message,
                     outcome.exit_code);
  }
  py::object summary = py::module_::import("json").attr("loads")(outcome.summary.to_json().dump());
  return py::make_tuple(summary, PythonResult(options.output_path));
}

}  // namespace tmdem::python
