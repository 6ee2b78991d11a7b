// The tmdem program: contract section 1. Everything is in tmdem_main (coupling/app/TmdemMain.h),
// after the OpenMP threads and wait are settled (OpenMpWaitPolicy.h).
#include <iostream>

#include "coupling/app/OpenMpWaitPolicy.h"
#include "coupling/app/TmdemMain.h"
#include "coupling/common/ExitCode.h"
#include "thermal/integrators/MpiWorld.h"

int main(int argc, char** argv) {
  // Under `mpirun -np N` (N > 1) MPI starts here; a serial run never starts it (MpiWorld.h).
  if (const auto problem = tmdem::thermal::MpiWorld::start_if_launched(&argc, &argv);
      !problem.empty()) {
    std::cerr << "error: " << problem << std::endl;
    return tmdem::coupling::kExitInvalid;
  }
  tmdem::coupling::settle_openmp_defaults(argv);
  return tmdem::coupling::tmdem_main(argc, argv);
}
