#include "coupling/app/OpenMpWaitPolicy.h"

#include <cstdlib>
#include <unistd.h>

namespace tmdem::coupling {

void prefer_passive_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: no /proc or no exec. The variable is set for child processes only; go on.
}

}  // namespace tmdem::coupling
