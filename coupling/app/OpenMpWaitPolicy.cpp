#include "coupling/app/OpenMpWaitPolicy.h"

#include <cstdlib>
#include <unistd.h>

namespace tmdem::coupling {

void prefer_passive_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  // Started by mpirun (OpenMPI 4.1): MPI_Init fails in a re-executed process ("getting local
  // rank failed"), so leave it; `mpirun -x OMP_WAIT_POLICY=passive` sets it instead.
  if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: no /proc or no exec. The variable is set for child processes only; go on.
}

}  // namespace tmdem::coupling
