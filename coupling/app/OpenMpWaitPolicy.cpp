#include "coupling/app/OpenMpWaitPolicy.h"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace tmdem::coupling {
namespace {

bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr;
}

}  // namespace

int idle_cores(int cores, double load) {
  cores = std::max(1, cores);
  if (!std::isfinite(load) || load < 0.0) return cores;
  return static_cast<int>(std::clamp<double>(cores - std::round(load), 1.0, cores));
}

int idle_cores() {
  double load = NAN;
  std::ifstream in("/proc/loadavg");
  in >> load;
  return idle_cores(omp_get_num_procs(), load);
}

void settle_openmp_defaults(char** argv) {
  // Started by mpirun (OpenMPI 4.1): MPI_Init fails in a re-executed process ("getting local
  // rank failed"), so no re-execution (`mpirun -x GOMP_SPINCOUNT=10000` sets the spin), and one
  // thread per process: the processes already share the cores.
  if (launched_by_mpirun()) {
    if (std::getenv("OMP_NUM_THREADS") == nullptr) omp_set_num_threads(1);
    return;
  }
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr &&
      setenv("GOMP_SPINCOUNT", kSpinCount, 1) == 0) {
    // The program's own path, not /proc/self/exe, so that ps and top still say "tmdem".
    char self[4096];
    const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
    if (length > 0) {
      self[length] = '\0';
      execv(self, argv);
    }
    // Still here: no /proc or no exec. The variable is set for child processes only; go on.
  }
  if (std::getenv("OMP_NUM_THREADS") == nullptr) omp_set_num_threads(idle_cores());
}

}  // namespace tmdem::coupling
