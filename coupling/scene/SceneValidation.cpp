#include "coupling/scene/SceneValidation.h"

#include "coupling/scene/SceneBuilder.h"
#include "coupling/scene/SceneError.h"
#include "mechanics/ParticleSet.h"
#include "mechanics/TouchingPairs.h"

namespace tmdem::coupling {

namespace {

std::string describe_particle(const Scene& scene, const std::vector<std::string>& origins,
                              std::size_t i) {
  const Particle& p = scene.particles[i];
  return "particle " + std::to_string(i) + " from " + origins[i] + " at " +
         format_vec3(p.position_m) + " with radius " + format_number(p.radius_m);
}

}  // namespace

void check_overlaps(const Scene& scene, const std::vector<std::string>& origins,
                    const std::string& source) {
  mechanics::ParticleSet set;
  set.reserve(scene.particles.size());
  for (const auto& p : scene.particles) {
    const double mass = mechanics::sphere_mass(
        p.radius_m, scene.materials[static_cast<std::size_t>(p.material)].density_kg_per_m3);
    set.add(Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]), p.radius_m,
            mass, p.material, p.fixed);
  }
  // Sorted by (i, j): the first is the pair with the smallest ids.
  const auto overlaps = mechanics::find_overlaps(set, kOverlapTolerance);
  if (!overlaps.empty()) {
    const auto a = static_cast<std::size_t>(overlaps.front().i);
    const auto b = static_cast<std::size_t>(overlaps.front().j);
    std::string more;
    if (overlaps.size() > 1)
      more = " (" + std::to_string(overlaps.size()) + " overlapping pairs in all)";
    throw SceneError(source + ": particles " + std::to_string(a) + " and " +
                     std::to_string(b) + " overlap at start (gap " +
                     format_number(overlaps.front().gap_m) +
                     " m, allowed down to -1e-9 x the smaller radius)" + more + ": " +
                     describe_particle(scene, origins, a) + "; " + describe_particle(scene, origins, b));
  }
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    const Wall& wall = scene.walls[w];
    for (std::size_t i = 0; i < scene.particles.size(); ++i) {
      const Particle& p = scene.particles[i];
      const double gap = wall_signed_distance(wall, p.position_m) - p.radius_m;
      if (gap < -kOverlapTolerance * p.radius_m)
        throw SceneError(source + ": particle " + std::to_string(i) + " and wall[" +
                         std::to_string(w) + "] overlap at start (gap " + format_number(gap) +
                         " m; the wall normal points into the domain): " +
                         describe_particle(scene, origins, i));
    }
  }
}

}  // namespace tmdem::coupling
