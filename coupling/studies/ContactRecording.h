#pragma once
// The contact graph of a dynamic run, step by step. The mechanics does not depend on the
// temperatures, so studies record it once and replay the thermal side against it as often as
// they like: every variant then sees exactly the same network and only thermal cost is timed.
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

struct ContactRecording {
  std::vector<double> step_end_s;        // end time of each mechanical step
  std::vector<ContactList> contacts;     // active contacts of that step, canonical order
  double mechanics_wall_time_s = 0.0;
};

// Runs the scene's NSCD mechanics (effects.mechanics = "dynamic") from t = 0 to the duration.
ContactRecording record_contacts(const Scene& scene, ProgressReporter& progress);

}  // namespace tmdem::coupling
