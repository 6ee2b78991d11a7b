#pragma once
// `tmdem check`: what the scene holds and how stiff its thermal problem will be, without running.
#include <ostream>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// Prints particles, materials, walls, effects and modes, and the thermal diagnostics on the
// contacts known before any mechanics step: the touching pairs, with the normal force estimated
// as the particle's weight m|g| for the Hertz law (the real forces come from settling).
void check_scene(const Scene& scene, std::ostream& out);

}  // namespace tmdem::coupling
