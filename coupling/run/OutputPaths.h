#pragma once
// The files a run will write, checked before anything is written (no file is ever lost
// silently): the result must not be empty, must not be the scene file, must not exist unless
// --overwrite (or --restart, which continues it); the summary and checkpoint may not be the scene
// or the result; and every folder must exist and be writable.
#include <string>

namespace tmdem::coupling {

struct OutputPathProblem {
  int exit_code = 0;    // 0: none; kExitInvalid for a refused path, kExitIo for an unusable one
  std::string message;  // names the file
};

struct OutputPaths {
  std::string scene;       // the scene file read (empty: the built-in scene)
  std::string result;
  std::string summary;     // empty: none
  std::string checkpoint;  // where checkpoints would go
  std::string step_log;    // --step-log: empty: none
  bool checkpoints = false;
  bool overwrite = false;  // --overwrite
  bool restart = false;    // --restart: the result must exist and is continued
};

OutputPathProblem check_output_paths(const OutputPaths& paths);

}  // namespace tmdem::coupling
