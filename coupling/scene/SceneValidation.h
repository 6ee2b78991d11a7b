#pragma once
// Checks across a whole built scene (the validate step of SceneLoader): particles overlapping
// each other (mechanics::find_overlaps) or a wall at start (gap < -1e-9 r) are SceneErrors
// naming the particle ids, where each came from, and the wall index.
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// origins: per particle, the entry that made it ("particle[3]", "generate[0]").
void check_overlaps(const Scene& scene, const std::vector<std::string>& origins,
                    const std::string& source);

}  // namespace tmdem::coupling
