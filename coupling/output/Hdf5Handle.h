#pragma once
// Owns one HDF5 identifier and closes it on every path (normal return, exception, move).
//
// tmdem uses HDF5 through its C API only (result file and checkpoints alike). The C++ wrapper
// (H5Cpp) adds a second exception hierarchy and its own global teardown order, and it has no
// wrapper for what the result writer needs anyway (file locking properties, H5Dset_extent on
// chunked datasets, the error stack walk that names the innermost cause): with one API, every
// identifier is owned by a Handle and every failure becomes one Hdf5Failure message.
#include <hdf5.h>

#include <stdexcept>
#include <utility>

namespace tmdem::coupling {

// An HDF5 call failed; the public functions turn it into an OutputError naming the file.
struct Hdf5Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Hdf5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Hdf5Handle() = default;
  Hdf5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Hdf5Handle(Hdf5Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  ~Hdf5Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes; returns false if closing failed (for files: the last flush failed). The id is
  // released either way, so nothing is left open for HDF5's own teardown at exit.
  bool reset() noexcept {
    bool ok = true;
    if (id_ >= 0 && closer_ != nullptr) ok = closer_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

}  // namespace tmdem::coupling
