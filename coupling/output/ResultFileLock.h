#pragma once
// The writer's claim on a result file for the whole run, so that a second tmdem writing the same
// file is refused (with the file named) instead of both "succeeding" into one broken file.
//
// Why not HDF5's own file lock: HDF5 (1.10, non-SWMR) takes an exclusive flock() on a file opened
// for writing and keeps it until the file is closed, and every reader with default settings
// (h5py, ParaView, another tmdem) asks for a shared flock() and is then refused. The contract
// promises that a running result is readable up to its last frame, so the writer cannot hold
// that lock. Instead it holds an open-file-description record lock (fcntl F_OFD_SETLK, write
// lock over the whole file): record locks and flock() locks do not interact on Linux, so readers
// keep working, while every tmdem writer (new run, --overwrite, --restart) asks for the same
// record lock before it touches a byte and is refused while another holds it. The lock goes
// away with the process, also after a crash or SIGKILL, so no stale lock files are left.
// (On NFS, Linux emulates flock() with record locks; there readers need
// HDF5_USE_FILE_LOCKING=FALSE while a run writes.)
#include <string>

namespace tmdem::coupling {

class ResultFileLock {
 public:
  ResultFileLock() = default;
  // Opens (creating it when `create` is set, never truncating) and locks `path`. Throws
  // OutputError naming the file if another process holds the lock or the file cannot be
  // opened. `created` tells whether this call created the file.
  ResultFileLock(const std::string& path, bool create);
  ResultFileLock(ResultFileLock&& other) noexcept;
  ResultFileLock& operator=(ResultFileLock&& other) noexcept;
  ResultFileLock(const ResultFileLock&) = delete;
  ResultFileLock& operator=(const ResultFileLock&) = delete;
  ~ResultFileLock();

  bool created() const { return created_; }
  void release();

 private:
  int fd_ = -1;
  bool created_ = false;
};

}  // namespace tmdem::coupling
