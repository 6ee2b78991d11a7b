#pragma once
// Checks across a whole built scene (the validate step of SceneLoader): particles overlapping
// each other (mechanics::find_overlaps) or a wall at start are SceneErrors naming the particle
// ids, where each came from, and the wall index. The allowed overlap is 1e-9 of the smaller
// radius (of the particle's radius against a wall), except between two particles of the same
// [[import]] and between such a particle and a wall, where that import's overlap_tolerance
// applies (settled packings overlap slightly).
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// origins: per particle, the entry that made it ("particle[3]", "generate[0]").
// import_of: per particle, its index into scene.imports, or -1. Fills each import's largest
// overlap (ImportReport::largest_overlap*).
void check_overlaps(Scene& scene, const std::vector<std::string>& origins,
                    const std::vector<int>& import_of, const std::string& source);

}  // namespace tmdem::coupling
