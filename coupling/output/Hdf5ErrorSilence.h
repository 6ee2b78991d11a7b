#pragma once
// Keeps HDF5 from printing its error stack to stderr while alive; errors are reported by
// exceptions instead.
#include <H5Epublic.h>

namespace tmdem::coupling {

class Hdf5ErrorSilence {
 public:
  Hdf5ErrorSilence() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~Hdf5ErrorSilence() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  Hdf5ErrorSilence(const Hdf5ErrorSilence&) = delete;
  Hdf5ErrorSilence& operator=(const Hdf5ErrorSilence&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace tmdem::coupling
