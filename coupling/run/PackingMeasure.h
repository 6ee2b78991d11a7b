#pragma once
// A settled bed's height and porosity, as experiments report them: the bed is taken as the box
// that bounds its particles (each axis from the lowest particle surface to the highest), its
// height along gravity, and its porosity 1 - (sum of the spheres' volumes) / (the box's volume).
// For a bed filling a rectangular container this is the porosity up to the top of the highest
// sphere (Lethe's measure); a cylindrical container's bed is over-counted (the box's corners are
// empty), so none is given for a scene with a cylinder wall. 3D with gravity only.
#include <optional>

#include "coupling/scene/Scene.h"
#include "mechanics/model/ParticleSet.h"

namespace tmdem::coupling {

struct PackingMeasure {
  double bed_height_m = 0.0;  // extent of the particles along gravity
  double porosity = 0.0;      // of their bounding box
};

std::optional<PackingMeasure> measure_packing(const Scene& scene, const mechanics::ParticleSet& particles);

}  // namespace tmdem::coupling
