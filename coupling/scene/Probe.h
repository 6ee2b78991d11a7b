#pragma once
// A [[probe]] of the scene: a region around a point whose particles (by centre) the result file
// summarises every frame, the way an experiment reads a thermocouple (mean, min and max
// temperature and the count of particles inside: /probes, docs/result-file.md).
#include <array>
#include <string>

namespace tmdem::coupling {

struct Probe {
  std::string name;                // unique among the probes; the result's /probes/names
  std::array<double, 3> point_m{};  // centre of the sphere or of the box
  double radius_m = 0.0;           // > 0: a sphere of this radius; 0: the box below
  std::array<double, 3> box_m{};   // full edge lengths of the axis-aligned box (radius_m == 0)
  bool is_box() const { return radius_m == 0.0; }
};

}  // namespace tmdem::coupling
