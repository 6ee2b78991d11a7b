#pragma once
// [[probe]] tables: their schema section (kept out of SceneSchema.cpp's list so the probes live
// in one file) and their reading into Scene::probes. Keys: name (required, unique), point
// (required), and exactly one of radius (a sphere) or box (full edge lengths of an axis-aligned
// box centred on point).
#include <vector>

#include "coupling/scene/Probe.h"
#include "coupling/scene/SceneSchema.h"
#include "coupling/scene/SceneTable.h"

namespace tmdem::coupling {

// The "probe" section of the schema (SceneSchema::sections() lists it; docs/scene.md shows it).
SceneSchema::Section probe_schema_section();
// The top-level key declaring [[probe]].
SceneSchema::Key probe_schema_key();

// Every [[probe]] of the root table, checked; SceneError naming probe[k].key otherwise.
std::vector<Probe> read_probes(const SceneTable& root, int dimension);

}  // namespace tmdem::coupling
