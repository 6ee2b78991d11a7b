#pragma once
// The CSV file of a study command: opened before the computation (an unwritable path fails
// before minutes of work), removed when the study fails, closed and checked at the end.
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>

#include "coupling/common/ExitCode.h"

namespace tmdem::coupling {

class StudyCsvFile {
 public:
  // An empty path: no CSV, every call does nothing and succeeds.
  explicit StudyCsvFile(std::string path) : path_(std::move(path)) {}

  // False (after one error line on log) when the file cannot be created.
  bool open(std::ostream& log) {
    if (path_.empty()) return true;
    file_.open(path_);
    if (!file_) log << "error: cannot write CSV file '" << path_ << "'" << std::endl;
    return bool(file_);
  }
  // Removes the file (the study failed: no half table).
  void discard() {
    if (path_.empty()) return;
    file_.close();
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  // Runs the study: `compute` returns an exit code, kExitOk to go on. Any other code, and any
  // exception, removes the file. A SolverError (what the study's solver throws when it fails)
  // is logged as one error line and gives kExitSolverFailed; other exceptions propagate.
  template <class SolverError, class Compute>
  int compute_or_discard(Compute&& compute, std::ostream& log) {
    try {
      const int code = compute();
      if (code != kExitOk) discard();
      return code;
    } catch (const SolverError& e) {
      log << "error: " << e.what() << std::endl;
      discard();
      return kExitSolverFailed;
    } catch (...) {
      discard();
      throw;
    }
  }
  // Writes the table through `write`, closes; false (after one error line) when writing failed.
  bool write(const std::function<void(std::ostream&)>& write, std::ostream& log, bool quiet) {
    if (path_.empty()) return true;
    write(file_);
    file_.close();
    if (!file_) {
      log << "error: writing CSV file '" << path_ << "' failed" << std::endl;
      return false;
    }
    if (!quiet) log << "wrote " << path_ << std::endl;
    return true;
  }

 private:
  std::string path_;
  std::ofstream file_;
};

}  // namespace tmdem::coupling
