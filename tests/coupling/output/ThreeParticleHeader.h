#pragma once
// The result header the output tests share: two 1 mm spheres of material 0 and one 2 mm sphere
// of material 1 (masses and capacities those of equal density), with no walls yet.
#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling::test {

inline ResultHeader three_particle_header() {
  ResultHeader header;
  header.radius_m = {1e-3, 1e-3, 2e-3};
  header.mass_kg = {1e-5, 1e-5, 8e-5};                // kg
  header.heat_capacity_J_per_K = {1e-2, 1e-2, 8e-2};  // J/K
  header.material = {0, 0, 1};
  return header;
}

}  // namespace tmdem::coupling::test
