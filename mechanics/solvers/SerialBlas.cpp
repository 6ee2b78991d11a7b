#include "mechanics/solvers/SerialBlas.h"

#include <dlfcn.h>

namespace tmdem::mechanics {
namespace {

// OpenBLAS's own calls, looked up once; both null when the process's BLAS is not OpenBLAS.
struct OpenBlasThreads {
  int (*get)() = nullptr;
  void (*set)(int) = nullptr;
};
const OpenBlasThreads& openblas() {
  static const OpenBlasThreads calls = [] {
    OpenBlasThreads found;
    found.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    found.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    if (found.get == nullptr || found.set == nullptr) found = {};
    return found;
  }();
  return calls;
}

}  // namespace

int SerialBlas::threads() { return openblas().get != nullptr ? openblas().get() : 0; }

void SerialBlas::set_threads(int count) {
  if (openblas().set != nullptr) openblas().set(count);
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
