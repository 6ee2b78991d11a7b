#include "mechanics/solvers/SerialBlas.h"

#include <dlfcn.h>

namespace tmdem::mechanics {
namespace {

using GetThreads = int (*)();
using SetThreads = void (*)(int);

// OpenBLAS's own calls, when the process's BLAS is OpenBLAS (looked up once).
GetThreads openblas_get() {
  static const auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get;
}
SetThreads openblas_set() {
  static const auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  return set;
}

}  // namespace

int SerialBlas::threads() {
  const GetThreads get = openblas_get();
  return get != nullptr && openblas_set() != nullptr ? get() : 0;
}

void SerialBlas::set_threads(int count) {
  if (const SetThreads set = openblas_set(); set != nullptr && openblas_get() != nullptr) set(count);
}

SerialBlas::SerialBlas() : before_(threads()) {
  if (before_ > 1) {
    set_threads(1);
  } else {
    before_ = 0;  // already serial, or not OpenBLAS: nothing to give back
  }
}

SerialBlas::~SerialBlas() {
  if (before_ > 1) set_threads(before_);
}

}  // namespace tmdem::mechanics
