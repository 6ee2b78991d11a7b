#include "coupling/app/TmdemMain.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "coupling/app/AccuracyCommand.h"
#include "coupling/app/ConductivityCommand.h"
#include "coupling/app/ContactProblemCommand.h"
#include "coupling/app/ExportCommand.h"
#include "coupling/app/ProbesCommand.h"
#include "coupling/app/RenderCommand.h"
#include "coupling/common/ExitCode.h"
#include "coupling/run/CoupledRun.h"
#include "coupling/studies/CouplingStudy.h"
#include "coupling/scene/DefaultScene.h"
#include "coupling/scene/ParticleImport.h"
#include "coupling/run/MechanicsStepLog.h"
#include "coupling/output/OutputError.h"
#include "coupling/app/RunEndReport.h"
#include "coupling/app/SceneCheck.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "coupling/scene/SceneReference.h"
#include "coupling/scene/TomlWriter.h"
#include "thermal/integrators/MpiWorld.h"

namespace tmdem::coupling {

namespace {

// An argument as the shell needs it in the resume hint.
std::string shell_quoted(const std::string& text) {
  if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-+=./:,@") == std::string::npos)
    return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

Scene load(const std::string& path, const std::vector<std::string>& sets) {
  return path.empty() ? load_default_scene(sets) : load_scene_file(path, sets);
}

}  // namespace

int tmdem_main(int argc, char** argv) {
  CLI::App app{"tmdem: heat flow through granular packings (NSCD mechanics, implicit thermal "
               "network)"};
  app.set_version_flag("--version", std::string("tmdem ") + TMDEM_VERSION);
  app.require_subcommand(1);

  std::string scene_path, output, summary, restart, step_log;
  std::vector<std::string> sets;
  bool quiet = false, overwrite = false;
  auto* run = app.add_subcommand("run", "run a scene (default: the built-in paper bed)");
  run->add_option("scene", scene_path, "scene file (TOML)");
  auto* output_option =
      run->add_option("-o,--output", output, "result file (overrides output.file)");
  run->add_option("--set", sets, "override one scene value, KEY=VALUE (TOML value)")
      ->take_all()->allow_extra_args(false);
  run->add_option("--summary", summary, "write the run summary (JSON) here");
  run->add_option("--restart", restart, "continue from a checkpoint file");
  run->add_option("--step-log", step_log,
                  "write one CSV line per mechanics step here: sweeps, residuals, retries, times "
                  "(docs/step-log.md)");
  run->add_flag("--overwrite", overwrite, "replace an existing result file");
  run->add_flag("--quiet", quiet, "no progress on stderr");

  std::string check_path;
  auto* check = app.add_subcommand("check", "validate a scene; print its contents and stiffness");
  check->add_option("scene", check_path, "scene file (TOML)")->required();
  check->add_option("--set", sets, "override one scene value, KEY=VALUE")->allow_extra_args(false);

  auto* study = app.add_subcommand("study", "numerical studies");
  std::string study_path;
  auto* accuracy = study->add_subcommand("accuracy", "work-precision study of the thermal integrators");
  accuracy->add_option("scene", study_path, "scene file (TOML)")->required();
  AccuracyCommandOptions study_options;
  accuracy->add_option("--csv", study_options.csv_path, "write the table as CSV here");
  accuracy->add_option("--set", sets, "override one scene value, KEY=VALUE (TOML value)")
      ->take_all()->allow_extra_args(false);
  accuracy->add_flag("--quiet", study_options.quiet, "no progress on stderr");
  accuracy->add_option("--explicit-rungs", study_options.study.explicit_rungs,
                       "explicit steps: 0.9 x the stability bound, then / 4 per rung (default 12)")
      ->check(CLI::Range(0, 30));
  accuracy->add_option("--explicit-budget", study_options.study.explicit_work_budget,
                       "skip explicit rungs whose steps x (particles + edges) exceed this "
                       "(default 2e9, a few seconds)")
      ->check(CLI::PositiveNumber);
  accuracy->add_option("--implicit-budget", study_options.study.implicit_time_budget_s,
                       "s: skip an implicit run predicted to take longer, and its method's "
                       "tighter tolerances once one of its runs took longer (default 60)")
      ->check(CLI::NonNegativeNumber);
  accuracy->add_option("--time-budget", study_options.study.study_time_budget_s,
                       "s: skip any run predicted to end the study (reference included) past "
                       "this (default 180)")
      ->check(CLI::NonNegativeNumber);
  std::vector<std::string> accuracy_methods;
  accuracy->add_option("--methods", accuracy_methods,
                       "implicit methods to study, INTEGRATOR/LINEAR_SOLVER separated by commas "
                       "(default cvode/klu,cvode/pcg,ida/klu,ida/pcg; e.g. add cvode/amg on large "
                       "beds)")
      ->delimiter(',');
  std::string coupling_path, coupling_csv;
  auto* coupling = study->add_subcommand(
      "coupling", "compare how the thermal side follows a dynamic packing (continue, restart, explicit)");
  coupling->add_option("scene", coupling_path, "scene file (TOML) with effects.mechanics = \"dynamic\"")
      ->required();
  coupling->add_option("--csv", coupling_csv, "write the table as CSV here");
  coupling->add_option("--set", sets, "override one scene value, KEY=VALUE")->allow_extra_args(false);
  std::string conductivity_path;
  ConductivityCommandOptions conductivity_options;
  auto* conductivity = study->add_subcommand(
      "conductivity", "effective conductivity of a bed between its two isothermal walls "
                      "(steady state: KLU, or multigrid CG with thermal.linear_solver = amg, "
                      "or auto on a large bed)");
  conductivity->add_option("scene", conductivity_path, "scene file (TOML)")->required();
  conductivity->add_option("--pressures", conductivity_options.pressures_Pa,
                           "piston pressures, Pa (needs a piston)")
      ->delimiter(',');
  conductivity->add_option("--csv", conductivity_options.csv_path, "write the table as CSV here");
  conductivity->add_option("--step-log", conductivity_options.step_log_path,
                           "write one CSV line per settle step here (docs/step-log.md)");
  conductivity->add_option("--set", sets, "override one scene value, KEY=VALUE (TOML value)")
      ->take_all()->allow_extra_args(false);
  conductivity->add_flag("--quiet", conductivity_options.quiet, "no progress on stderr");
  study->require_subcommand(1);

  ExportOptions export_options;
  auto* export_command = app.add_subcommand(
      "export", "write one frame of a result (default: the last) as CSV, in the columns "
                "[[import]] reads");
  export_command->add_option("result", export_options.result_path, "result file (HDF5)")->required();
  export_command->add_option("--frame", export_options.frame,
                             "\"last\" (default) or a frame number; negative counts from the end");
  export_command->add_option("-o,--output", export_options.csv_path, "CSV file to write")->required();
  export_command->add_flag("--overwrite", export_options.overwrite, "replace an existing CSV file");

  ProbesOptions probes_options;
  auto* probes = app.add_subcommand(
      "probes", "the [[probe]] readings of a result as CSV: time_s,probe,count,mean_K,min_K,max_K "
                "(count 0: no particle inside, temperatures then 0)");
  probes->add_option("result", probes_options.result_path, "result file (HDF5)")->required();
  probes->add_option("-o,--output", probes_options.csv_path,
                     "CSV file to write (replaced if it exists; default: stdout)");

  RenderOptions render_options;
  auto* render = app.add_subcommand(
      "render", "draw one frame of a result (default: the last) as a PNG with ParaView's pvbatch: "
                "spheres coloured by temperature over that frame's range");
  render->add_option("result", render_options.result_path, "result file (HDF5; RESULT.xdmf next to it)")
      ->required();
  render->add_option("-o,--output", render_options.png_path, "PNG file to write (replaced if it exists)")
      ->required();
  render->add_option("--frame", render_options.frame,
                     "\"last\" (default) or a frame number; negative counts from the end");
  render->add_option("--cut", render_options.cut,
                     "draw only the spheres below the bed's mid-plane normal to this axis, "
                     "looking at the cut")
      ->check(CLI::IsMember({"x", "y", "z"}));
  render->add_flag("--forces", render_options.forces,
                   "draw the contact force network as tubes (radius grows with the normal force)");
  render->add_option("--size", render_options.size, "image width and height in pixels (1200 900)")
      ->expected(2)->check(CLI::Range(64, 8192));
  std::string problem_scene;
  ContactProblemOptions problem_options;
  auto* contact_problem = app.add_subcommand(
      "contact-problem", "write one mechanical step's contact problem (FCLIB local format, "
                         "HDF5) with tmdem's reactions as its solution");
  contact_problem->add_option("scene", problem_scene, "scene file (TOML)")->required();
  contact_problem->add_option("--step", problem_options.step,
                              "mechanical step, 1 the first, or \"last\" (the settled packing "
                              "of a settle scene)")
      ->required();
  contact_problem->add_option("-o,--output", problem_options.output_path, "FCLIB file to write")
      ->required();
  contact_problem->add_option("--set", sets, "override one scene value, KEY=VALUE (TOML value)")
      ->take_all()->allow_extra_args(false);
  contact_problem->add_flag("--overwrite", problem_options.overwrite, "replace an existing file");

  auto* docs = app.add_subcommand("docs", "print generated reference documentation");
  auto* docs_scene = docs->add_subcommand(
      "scene", "the scene file reference (Markdown): every key with unit, default, range");
  auto* docs_step_log = docs->add_subcommand(
      "step-log", "the step log's columns (Markdown; tmdem run --step-log)");
  docs->require_subcommand(1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitInvalid;
  }

  // Over MPI every process reads the same scene and meets the same error in it: rank 0 says it.
  const auto say_error = [](const std::exception& e) {
    if (thermal::MpiWorld::rank() == 0) std::cerr << "error: " << e.what() << std::endl;
  };
  // Every other command would run whole in each process, all writing the same files.
  if (thermal::MpiWorld::distributed() && !*run) {
    if (thermal::MpiWorld::rank() == 0)
      std::cerr << "error: only `tmdem run` runs over MPI (started as one of "
                << thermal::MpiWorld::size() << " processes); run this command without mpirun"
                << std::endl;
    return kExitInvalid;
  }

  try {
    if (*run) {
      if (output_option->count() > 0 && output.empty()) {
        std::cerr << "error: -o needs a file name (got an empty one)" << std::endl;
        return kExitInvalid;
      }
      // Over MPI rank 0 speaks for all (the others only of a failure of their own, CoupledRun).
      const bool speaks = thermal::MpiWorld::rank() == 0;
      // -o overrides output.file: the result file's resolved scene (its "scene" attribute) says so.
      std::vector<std::string> resolved_sets = sets;
      if (!output.empty()) resolved_sets.push_back("output.file=" + toml_basic_string(output));
      const Scene scene = load(scene_path, resolved_sets);
      if (!quiet && speaks)
        for (const auto& report : scene.imports) std::cerr << describe_import(report) << std::endl;
      // Even with --quiet (no progress): a warning is about the scene, not the run's progress.
      if (speaks)
        for (const auto& warning : scene.warnings) std::cerr << "warning: " << warning << std::endl;
      RunOptions options;
      options.output_path = output.empty()
                                ? (scene_path.empty() && scene.output.file.empty() ? "tmdem-default.h5"
                                                                                   : scene.output.file)
                                : output;
      options.scene_path = scene_path;
      options.overwrite = overwrite;
      // Over MPI, mpirun (OpenMPI 4.1) passes SIGINT on as SIGTERM and kills every process
      // within a second or two, before a frame could be finished: its handling applies, and the
      // run resumes from its last output.checkpoint_interval checkpoint.
      options.handle_signals = !thermal::MpiWorld::distributed();
      options.resume_command = "tmdem run" + (scene_path.empty() ? "" : " " + shell_quoted(scene_path));
      for (const auto& set : sets) options.resume_command += " --set " + shell_quoted(set);
      options.resume_command += " -o " + shell_quoted(options.output_path);
      if (!step_log.empty()) options.resume_command += " --step-log " + shell_quoted(step_log);
      options.summary_path = summary;
      options.step_log_path = step_log;
      options.restart_path = restart;
      options.quiet = quiet || !speaks;
      options.terminal = isatty(STDERR_FILENO);
      const auto outcome = run_scene(scene, options, std::cerr);
      if (outcome.exit_code != kExitInvalid && speaks)  // a run refused at start did nothing to report
        print_run_end(outcome.summary, scene,
                      outcome.exit_code == kExitOk ? options.output_path : "", quiet, std::cerr);
      return outcome.exit_code;
    }
    if (*export_command) return run_export_command(export_options, std::cout, std::cerr);
    if (*probes) return run_probes_command(probes_options, std::cout, std::cerr);
    if (*render) return run_render_command(render_options, std::cout, std::cerr);
    if (*contact_problem)
      return run_contact_problem_command(load_scene_file(problem_scene, sets), problem_options,
                                         std::cout, std::cerr);
    if (*docs_scene) {
      std::cout << scene_reference_markdown();
      return kExitOk;
    }
    if (*docs_step_log) {
      std::cout << MechanicsStepLog::reference_markdown();
      return kExitOk;
    }
    if (*check) {
      const Scene scene = load(check_path, sets);
      check_scene(scene, std::cout);
      std::cout << "scene is valid" << std::endl;
      return kExitOk;
    }
    if (*coupling) {
      const Scene scene = load_scene_file(coupling_path, sets);
      return run_coupling_study(scene, coupling_csv, std::cout, std::cerr);
    }
    if (*conductivity) {
      const Scene scene = load_scene_file(conductivity_path, sets);
      conductivity_options.terminal = isatty(STDERR_FILENO);
      conductivity_options.handle_signals = !thermal::MpiWorld::distributed();
      return run_conductivity_command(scene, conductivity_options, std::cout, std::cerr);
    }
    if (*accuracy) {
      if (!accuracy_methods.empty()) {
        std::string problem;
        study_options.study.implicit_methods = parse_implicit_methods(accuracy_methods, problem);
        if (!problem.empty()) {
          std::cerr << "error: --methods: " << problem << std::endl;
          return kExitInvalid;
        }
      }
      const Scene scene = load_scene_file(study_path, sets);
      study_options.terminal = isatty(STDERR_FILENO);
      study_options.handle_signals = !thermal::MpiWorld::distributed();
      return run_accuracy_command(scene, study_options, std::cout, std::cerr);
    }
  } catch (const SceneError& e) {
    say_error(e);
    return kExitInvalid;
  } catch (const OutputError& e) {
    say_error(e);
    return kExitIo;
  } catch (const std::exception& e) {
    say_error(e);
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace tmdem::coupling
