#pragma once
// The coupled time loop (contract section 1, `tmdem run`): mechanics produces the contact graph
// and normal forces, the network builder turns them into conductances, the thermal integrator
// advances the temperatures, and frames go to the result file.
//
//   mechanics = "off":     contacts from geometry once; thermal steps as large as the
//                          integrator likes between frames.
//   mechanics = "settle":  NSCD until at rest (before t = 0), then as "off" on the frozen graph.
//   mechanics = "dynamic": every mechanical step hands the new graph and forces over, and the
//                          thermal side advances over that step (see thermal.coupling).
#include <ostream>
#include <string>
#include <vector>

#include "coupling/output/RunSummary.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

struct RunOptions {
  std::string output_path;      // result file (scene's output.file unless -o)
  std::string summary_path;     // empty: no summary file
  std::string step_log_path;    // --step-log: one CSV line per mechanics step; empty: none
  std::string restart_path;     // empty: start at t = 0
  std::string scene_path;       // the scene file read (empty: built-in); never an output
  bool overwrite = false;       // --overwrite: an existing result file may be replaced
  std::string resume_command;   // "tmdem run SCENE ... -o RESULT" for the resume hint
  bool handle_signals = false;  // SIGINT/SIGTERM end the run cleanly (exit 130/143)
  bool quiet = false;
  bool terminal = false;        // stderr is a terminal: one updating progress line
};

struct RunOutcome {
  int exit_code = 0;            // an ExitCode (coupling/common/ExitCode.h)
  RunSummary summary;
  std::vector<double> final_temperature_K;  // at the last time reached
};

// Never throws for solver or output failures: they become exit codes with the message on `log`
// (and in summary.message). Settings refused at start (e.g. an explicit step above the
// stability bound, a result file that exists without --overwrite) give exit 2 before any file
// is written. With handle_signals, a first SIGINT/SIGTERM ends the run after the current step
// with a last frame, a checkpoint, status "interrupted" and exit 130/143.
RunOutcome run_scene(const Scene& scene, const RunOptions& options, std::ostream& log);

// Where checkpoints of a run writing `output_path` go: RESULT.checkpoint.h5.
std::string checkpoint_path_for(const std::string& output_path);

// The result a checkpoint belongs to (RESULT.checkpoint.h5 -> RESULT.h5); empty when the name
// is not of that form.
std::string result_path_for_checkpoint(const std::string& checkpoint_path);

}  // namespace tmdem::coupling
