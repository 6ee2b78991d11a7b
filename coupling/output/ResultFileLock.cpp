#include "coupling/output/ResultFileLock.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

ResultFileLock::ResultFileLock(const std::string& path, bool create) {
  int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC, 0644);
  if (fd < 0 && errno == ENOENT && create) {
    fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    created_ = fd >= 0;
  }
  if (fd < 0) {
    throw OutputError("cannot open result file '" + path + "': " + std::strerror(errno));
  }
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  lock.l_start = 0;
  lock.l_len = 0;  // the whole file, however long it grows
  if (::fcntl(fd, F_OFD_SETLK, &lock) != 0) {
    const int error = errno;
    ::close(fd);
    if (created_) ::unlink(path.c_str());
    if (error == EAGAIN || error == EACCES) {
      throw OutputError("result file '" + path +
                        "' is being written by another process (another tmdem run holds it); "
                        "wait for it to end or choose another -o");
    }
    throw OutputError("cannot lock result file '" + path + "': " + std::strerror(error));
  }
  fd_ = fd;
}

ResultFileLock::ResultFileLock(ResultFileLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), created_(other.created_) {}

ResultFileLock& ResultFileLock::operator=(ResultFileLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
    created_ = other.created_;
  }
  return *this;
}

ResultFileLock::~ResultFileLock() { release(); }

void ResultFileLock::release() {
  if (fd_ >= 0) ::close(fd_);  // closing the description drops its record lock
  fd_ = -1;
}

}  // namespace tmdem::coupling
