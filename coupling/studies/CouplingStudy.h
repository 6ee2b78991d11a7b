#pragma once
// `tmdem study coupling SCENE`: how the thermal side should follow a moving packing. Runs a
// dynamic scene with each coupled-step strategy and compares its final temperatures with a
// tightly resolved run (CVODE restarted every mechanical step at rtol 1e-12):
//   continue  CVODE keeps its history while contacts only change force; re-initialised (new
//             symbolic factorization) only when a new contact closes;
//   restart   CVODE re-initialised at every mechanical step;
//   explicit  forward Euler at the mechanical step (the MULTICOR way).
// The mechanics does not depend on the temperatures: it is run once, recorded, and replayed for
// every variant (ThermalReplay), so the differences and the times are the thermal side's alone.
#include <ostream>
#include <string>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// CSV header: strategy,integrator,parameter,max_error_K,thermal_wall_time_s,thermal_steps,
// reinitializations. Returns an exit code (0, 2 not a dynamic scene, 3 the
// reference failed, 4 I/O).
int run_coupling_study(const Scene& scene, const std::string& csv_path, std::ostream& out,
                       std::ostream& log);

}  // namespace tmdem::coupling
