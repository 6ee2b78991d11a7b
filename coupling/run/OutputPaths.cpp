#include "coupling/run/OutputPaths.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "coupling/common/ExitCode.h"

namespace tmdem::coupling {
namespace {

namespace fs = std::filesystem;

// Same file: the same existing inode, or the same absolute normalised path.
bool same_file(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return false;
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error);
  return fs::absolute(a, error).lexically_normal() == fs::absolute(b, error).lexically_normal();
}

// Why a file cannot be written at `path` (empty: it can): its folder must exist and be
// writable, and the path may not be a folder.
std::string unwritable(const std::string& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) return "it is a folder";
  const fs::path parent = fs::path(path).parent_path();
  const std::string folder = parent.empty() ? "." : parent.string();
  if (!fs::is_directory(folder, error)) return "folder '" + folder + "' does not exist";
  if (::access(folder.c_str(), W_OK) != 0) return "folder '" + folder + "' is not writable";
  if (fs::exists(path, error) && ::access(path.c_str(), W_OK) != 0) return "it is not writable";
  return {};
}

}  // namespace

OutputPathProblem check_output_paths(const OutputPaths& p) {
  auto refuse = [](const std::string& message) {
    return OutputPathProblem{kExitInvalid, message};
  };
  if (p.result.empty()) return refuse("the result file name is empty (-o \"\" or output.file)");
  if (same_file(p.result, p.scene)) {
    return refuse("result file '" + p.result + "' is the scene file; choose another -o");
  }
  if (same_file(p.summary, p.scene) || same_file(p.summary, p.result)) {
    return refuse("summary file '" + p.summary + "' is the scene or the result file");
  }
  if (p.checkpoints && (same_file(p.checkpoint, p.scene) || same_file(p.checkpoint, p.result))) {
    return refuse("checkpoint file '" + p.checkpoint + "' is the scene or the result file");
  }
  if (same_file(p.step_log, p.scene) || same_file(p.step_log, p.result) ||
      same_file(p.step_log, p.summary) || (p.checkpoints && same_file(p.step_log, p.checkpoint))) {
    return refuse("step log '" + p.step_log + "' is the scene, the result, the summary or the checkpoint file");
  }
  std::error_code error;
  if (!p.restart && !p.overwrite && fs::exists(p.result, error)) {
    return refuse("result file '" + p.result +
                  "' exists; give --overwrite to replace it, or another -o");
  }
  if (const std::string why = unwritable(p.result); !why.empty()) {
    return {kExitIo, "cannot write result file '" + p.result + "': " + why};
  }
  if (!p.summary.empty()) {
    if (const std::string why = unwritable(p.summary); !why.empty()) {
      return {kExitIo, "cannot write summary file '" + p.summary + "': " + why};
    }
  }
  if (!p.step_log.empty()) {
    if (const std::string why = unwritable(p.step_log); !why.empty()) {
      return {kExitIo, "cannot write step log '" + p.step_log + "': " + why};
    }
  }
  if (p.checkpoints) {
    if (const std::string why = unwritable(p.checkpoint); !why.empty()) {
      return {kExitIo, "cannot write checkpoint '" + p.checkpoint + "': " + why};
    }
  }
  return {};
}

}  // namespace tmdem::coupling
