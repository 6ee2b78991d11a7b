#pragma once
// A pile poured into a box periodic along x and z (16 mm periods) onto a floor y = 0: the
// random_pile of MechanicsTestScenes.h without side walls.

#include "mechanics/MechanicsTestScenes.h"

namespace tmdem::mechanics::test {

inline constexpr double kPeriodicWidth = 0.016;  // m, the period along x and z

inline PeriodicBox periodic_xz_box() {
  PeriodicBox box;
  box.periodic = {true, false, true};
  box.high = Eigen::Vector3d(kPeriodicWidth, 0.0, kPeriodicWidth);
  return box;
}

inline NscdIntegrator periodic_pile(std::size_t count, double friction, std::uint64_t seed,
                                    NscdParameters parameters = nlgs_parameters()) {
  const auto placed = place_random(count, Eigen::Vector3d(0, 0, 0),
                                   Eigen::Vector3d(kPeriodicWidth, 0.012, kPeriodicWidth),
                                   {kRadius, 0.7 * kRadius}, {0.5, 0.5}, seed, 3);
  ParticleSet set;
  set.box = periodic_xz_box();
  for (std::size_t i = 0; i < count; ++i)
    set.add(set.box.wrap(placed.positions[i]), placed.radii[i], sphere_mass(placed.radii[i], kDensity), 0);
  return NscdIntegrator(std::move(set), {steel(friction)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                        Eigen::Vector3d(0, -kG, 0), 3, parameters);
}

}  // namespace tmdem::mechanics::test
