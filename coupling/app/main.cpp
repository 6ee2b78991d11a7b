// The tmdem program: contract section 1. Everything is in tmdem_main (coupling/app/TmdemMain.h),
// after the OpenMP threads and wait are settled (OpenMpWaitPolicy.h).
#include "coupling/app/OpenMpWaitPolicy.h"
#include "coupling/app/TmdemMain.h"

int main(int argc, char** argv) {
  tmdem::coupling::settle_openmp_defaults(argv);
  return tmdem::coupling::tmdem_main(argc, argv);
}
