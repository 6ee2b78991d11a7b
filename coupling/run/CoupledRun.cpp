// The coupled run as a whole (CoupledRun.h): set up, loop, and end with the exit code, the
// status, the result file closed and the summary written, whatever happened in between. Its
// parts: CoupledRunSetup.cpp, CoupledRunLoops.cpp, CoupledRunThermoMechanics.cpp,
// CoupledRunResultFile.cpp, CoupledRunSummary.cpp, CoupledRunCheckpoints.cpp (state:
// CoupledRunLoop.h).
#include "coupling/run/CoupledRun.h"

#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include "coupling/common/ExitCode.h"
#include "coupling/output/Checkpoint.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/ResultWriter.h"
#include "coupling/run/CoupledRunLoop.h"
#include "coupling/run/DistributedHeating.h"
#include "coupling/run/Interruption.h"
#include "coupling/run/OutputPaths.h"
#include "coupling/run/RestartState.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::coupling {

std::string checkpoint_path_for(const std::string& output_path) {
  const std::string ext = ".h5";
  if (output_path.size() > ext.size() &&
      output_path.compare(output_path.size() - ext.size(), ext.size(), ext) == 0)
    return output_path.substr(0, output_path.size() - ext.size()) + ".checkpoint.h5";
  return output_path + ".checkpoint.h5";
}

std::string result_path_for_checkpoint(const std::string& checkpoint_path) {
  const std::string ext = ".checkpoint.h5";
  if (checkpoint_path.size() > ext.size() &&
      checkpoint_path.compare(checkpoint_path.size() - ext.size(), ext.size(), ext) == 0)
    return checkpoint_path.substr(0, checkpoint_path.size() - ext.size()) + ".h5";
  return "";
}

namespace run_detail {

RunOutcome CoupledRun::run() {
  RunOutcome outcome;
  // status: "ok", "failed" or "interrupted"; `message` is printed once as the error line, a
  // later failure while closing the files only when it says something new.
  auto finish = [&](int code, const std::string& message, std::string status) {
    progress_.done();
    // Over MPI rank 0 reports what every process met; another process speaks only for a failure
    // of its own.
    if (!message.empty() && (writes_files_ || local_failure_))
      log_ << (writes_files_ ? "" : "rank " + std::to_string(thermal::MpiWorld::rank()) + ": ")
           << "error: " << message << std::endl;
    auto report = [&](const OutputError& e) {
      // After a failure of the result file, closing it fails for the same reason: one line.
      const bool same_file = code != kExitOk && std::string(e.what()).find(
                                                    "'" + options_.output_path + "'") != std::string::npos;
      if (!same_file) log_ << "error: " << e.what() << std::endl;
      if (code == kExitOk) code = kExitIo, status = "failed";
    };
    summary_.status = status;
    summary_.message = message;
    fill_summary();
    if (writer_ && !writer_->finished()) {
      try {
        writer_->finish(status);
      } catch (const OutputError& e) {
        report(e);
      }
    }
    summary_.status = status;
    // A run refused at start writes nothing, not even a summary; over MPI rank 0 writes it.
    if (!options_.summary_path.empty() && code != kExitInvalid && writes_files_) {
      try {
        summary_.write(options_.summary_path);
      } catch (const OutputError& e) {
        report(e);
      }
    }
    // Over MPI a failure one process may meet alone (rank 0's files, an unexpected exception)
    // would leave the others waiting in their next collective call for ever: all end here.
    if (thermal::MpiWorld::distributed() && (code == kExitIo || local_failure_))
      thermal::MpiWorld::abort(code);
    outcome.exit_code = code;
    outcome.summary = summary_;
    if (integrator_) {
      const auto T = integrator_->temperatures_K();
      outcome.final_temperature_K.assign(T.begin(), T.end());
    }
    return outcome;
  };
  auto failed = [&](int code, const std::string& message) {
    return finish(code, message, code == kExitOk ? "ok" : "failed");
  };

  OutputPaths paths;
  paths.scene = options_.scene_path;
  paths.result = options_.output_path;
  paths.summary = options_.summary_path;
  paths.step_log = options_.step_log_path;
  paths.checkpoint = checkpoint_path_for(options_.output_path);
  paths.checkpoints = true;  // an interruption writes one even without checkpoint_interval
  paths.overwrite = options_.overwrite;
  paths.restart = !options_.restart_path.empty();
  // A settle checkpoint starts a new result file (no frame was written before it): the result
  // is checked as a fresh run's. A checkpoint that cannot be read is reported by
  // restore_checkpoint (exit 4).
  if (paths.restart) {
    try {
      restart_ = read_checkpoint(options_.restart_path);
      paths.restart = !restart_->settling;
    } catch (const OutputError&) {
    }
  }
  if (thermal::MpiWorld::distributed()) {
    if (const auto why = distributed_heating_refusal(scene_, thermal::MpiWorld::size());
        !why.empty())
      return failed(kExitInvalid, why);
  }
  // Over MPI rank 0 writes every file; the others learn whether it may.
  const auto problem = writes_files_ ? check_output_paths(paths) : OutputPathProblem{};
  if (const int code = thermal::MpiWorld::from_root(problem.exit_code); code != kExitOk)
    return failed(code, problem.message);

  std::optional<Interruption> interruption;
  if (options_.handle_signals) interruption.emplace(options_.quiet, nullptr, true);
  try {
    // Before the settle, whose steps it logs; a restart appends (MechanicsStepLog.h).
    if (writes_files_ && !options_.step_log_path.empty())
      step_log_.emplace(options_.step_log_path, !options_.restart_path.empty());
    restore_checkpoint();
    prepare_mechanics();
    prepare_thermal();
  } catch (const Interrupted& stop) {
    const int code = stop.signal == SIGINT ? kExitSigint : kExitSigterm;
    RunOutcome result = finish(code, "", "interrupted");
    if (result.exit_code == code)
      log_ << "interrupted by " << signal_name(stop.signal) << " while settling (after "
           << stop.time_s << " s of settle time); no result file yet; resume settling with: "
           << (options_.resume_command.empty() ? "tmdem run SCENE -o " + options_.output_path
                                               : options_.resume_command)
           << " --restart " << checkpoint_path_for(options_.output_path) << std::endl;
    return result;
  } catch (const StartError& e) {
    return failed(kExitInvalid, e.what());
  } catch (const OutputError& e) {
    return failed(kExitIo, e.what());
  } catch (const thermal::ThermalSolverError& e) {
    return failed(kExitSolverFailed, e.what());
  } catch (const std::exception& e) {
    local_failure_ = true;
    return failed(kExitSolverFailed, std::string("the run stopped before its first output: ") + e.what());
  }

  // Rank 0 opens the result file; over MPI the others must learn whether it could, or they
  // would wait for it for ever in the first step.
  int open_code = kExitOk;
  std::string open_message;
  try {
    if (writes_files_) open_result_file();
  } catch (const ResultMismatch& e) {
    open_code = kExitInvalid, open_message = e.what();
  } catch (const OutputError& e) {
    open_code = kExitIo, open_message = e.what();
  } catch (const std::exception& e) {
    open_code = kExitSolverFailed, open_message = e.what();
  }
  if (const int code = thermal::MpiWorld::from_root(open_code); code != kExitOk)
    return failed(code, open_message);

  try {
    next_checkpoint_s_ = scene_.output.checkpoint_interval_s > 0.0
                             ? next_checkpoint_time_s(t0_, scene_.output.checkpoint_interval_s)
                             : 0.0;
    if (frozen_)
      run_static();
    else if (scene_.effects.mechanics == MechanicsMode::Coupled)
      run_coupled();
    else
      run_dynamic();
  } catch (const Interrupted& stop) {
    const int code = stop.signal == SIGINT ? kExitSigint : kExitSigterm;
    const std::string checkpoint = checkpoint_path_for(options_.output_path);
    RunOutcome result = finish(code, "", "interrupted");
    if (result.exit_code == code) {
      log_ << "interrupted by " << signal_name(stop.signal) << " at t = " << stop.time_s
           << " s; resume with: "
           << (options_.resume_command.empty() ? "tmdem run SCENE -o " + options_.output_path
                                               : options_.resume_command)
           << " --restart " << checkpoint
           << std::endl;
    }
    return result;
  } catch (const thermal::ThermalSolverError& e) {
    return failed(kExitSolverFailed, e.what());
  } catch (const ResultMismatch& e) {
    return failed(writer_ ? kExitIo : kExitInvalid, e.what());
  } catch (const OutputError& e) {
    return failed(kExitIo, e.what());
  } catch (const std::exception& e) {
    local_failure_ = true;
    return failed(kExitSolverFailed, e.what());
  }
  if (settle_checkpoint_on_disk_) {  // the run is complete: its settle needs no resuming
    std::error_code error;
    std::filesystem::remove(checkpoint_path_for(options_.output_path), error);
  }
  return failed(kExitOk, "");
}

}  // namespace run_detail

RunOutcome run_scene(const Scene& scene, const RunOptions& options, std::ostream& log) {
  run_detail::CoupledRun run(scene, options, log);
  return run.run();
}

}  // namespace tmdem::coupling

