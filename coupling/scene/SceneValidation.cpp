#include "coupling/scene/SceneValidation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "coupling/scene/SceneBuilder.h"
#include "coupling/scene/SceneError.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/detection/TouchingPairs.h"

namespace tmdem::coupling {

namespace {

std::string describe_particle(const Scene& scene, const std::vector<std::string>& origins,
                              std::size_t i) {
  const Particle& p = scene.particles[i];
  return "particle " + std::to_string(i) + " from " + origins[i] + " at " +
         format_vec3(p.position_m) + " with radius " + format_number(p.radius_m);
}

// Records an overlap of `fraction` of the smaller radius in import `group` if it is the largest.
void note_overlap(Scene& scene, int group, double fraction, double gap_m, const std::string& between) {
  if (group < 0) return;
  ImportReport& report = scene.imports[std::size_t(group)];
  if (fraction > report.largest_overlap) {
    report.largest_overlap = fraction;
    report.largest_overlap_m = -gap_m;
    report.largest_overlap_between = between;
  }
}

std::string allowance(const Scene& scene, int group) {
  if (group < 0) return "allowed down to -1e-9 x the smaller radius";
  const ImportReport& report = scene.imports[std::size_t(group)];
  return "more than " + report.origin + ".overlap_tolerance = " +
         format_number(report.overlap_tolerance) +
         " of the smaller radius; raise it to accept the overlaps of a settled packing";
}

// What an import's tolerance must be to accept every overlap of its file (pairs and walls; the
// largest noted over both), rounded up to two significant digits, so that a user handed a
// packing made at a softened modulus need not guess: "" outside an import.
std::string needed_tolerance(const Scene& scene, int group) {
  if (group < 0) return "";
  const ImportReport& report = scene.imports[std::size_t(group)];
  if (!(report.largest_overlap > 0.0)) return "";
  const double scale = std::pow(10.0, std::floor(std::log10(report.largest_overlap)) - 1.0);
  double accepting = std::ceil(report.largest_overlap / scale) * scale;
  if (accepting < report.largest_overlap) accepting += scale;  // the rounding of the product
  return "; the deepest overlap of " + report.origin + " is " + format_number(report.largest_overlap) +
         " of the smaller radius (" + report.largest_overlap_between + "): overlap_tolerance = " +
         format_number(accepting) + " accepts every overlap of the file";
}

// What to do about particle i overlapping wall w at start, when a [[generate]] box placed it:
// the box-filling kinds place by their box alone and do not see the walls (a deposit in a
// cylinder given the cylinder's bounding square put its corner spheres through the wall).
std::string generated_overlap_hint(const Scene& scene, const std::string& origin, std::size_t w,
                                   std::size_t i) {
  if (!origin.starts_with("generate[")) return "";
  const Wall& wall = scene.walls[w];
  std::string hint = "; " + origin + " places its particles by its box alone, not by the walls: give it a box inside every wall";
  if (wall.cylinder) {
    // Across the axis, a square inscribed in the circle the centres may reach.
    const double half_width_m = (wall.radius_m - scene.particles[i].radius_m) / std::sqrt(2.0);
    std::ostringstream figures;  // six significant digits: 0.00806102 m, not 0.008061017305526642 m
    figures << " (across the axis of the cylinder wall[" << w << "], the centres of spheres of radius "
            << scene.particles[i].radius_m << " m fit in a square of half-width " << half_width_m << " m about it)";
    hint += figures.str();
  }
  return hint;
}

}  // namespace

void check_overlaps(Scene& scene, const std::vector<std::string>& origins,
                    const std::vector<int>& import_of, const std::string& source) {
  mechanics::ParticleSet set;
  set.box = periodic_box(scene.periodic);  // overlaps across a periodic boundary count too
  set.reserve(scene.particles.size());
  for (const auto& p : scene.particles) {
    const double mass = mechanics::sphere_mass(
        p.radius_m, scene.materials[static_cast<std::size_t>(p.material)].density_kg_per_m3);
    set.add(Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]), p.radius_m,
            mass, p.material, p.fixed);
  }
  // A pair may overlap by its group's tolerance when both particles come from the same import.
  const auto group_of = [&](std::size_t a, std::size_t b) {
    return import_of[a] >= 0 && import_of[a] == import_of[b] ? import_of[a] : -1;
  };
  const auto tolerance = [&](int group) {
    return group < 0 ? kOverlapTolerance : scene.imports[std::size_t(group)].overlap_tolerance;
  };
  // Every overlapping pair, sorted by (i, j): the first refused is the one with the smallest ids.
  const auto overlaps = mechanics::find_overlaps(set, 0.0);
  const mechanics::TouchingPair* refused = nullptr;
  std::size_t refused_count = 0;
  for (const auto& pair : overlaps) {
    const auto a = static_cast<std::size_t>(pair.i), b = static_cast<std::size_t>(pair.j);
    const double fraction = -pair.gap_m / std::min(set.radius[a], set.radius[b]);
    const int group = group_of(a, b);
    note_overlap(scene, group, fraction, pair.gap_m,
                 "particles " + std::to_string(a) + " and " + std::to_string(b));
    if (fraction > tolerance(group)) {
      if (refused == nullptr) refused = &pair;
      ++refused_count;
    }
  }
  // The walls before any refusal, so that an import's deepest overlap (needed_tolerance) is
  // known over its pairs and its walls alike; the first refused of each kind is reported.
  struct WallOverlap {
    std::size_t wall, particle;
    double gap_m;
  };
  std::optional<WallOverlap> refused_wall;
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    const Wall& wall = scene.walls[w];
    for (std::size_t i = 0; i < scene.particles.size(); ++i) {
      const Particle& p = scene.particles[i];
      const double gap = wall_signed_distance(wall, p.position_m) - p.radius_m;
      if (!(gap < 0.0)) continue;
      const int group = import_of[i];
      note_overlap(scene, group, -gap / p.radius_m, gap,
                   "particle " + std::to_string(i) + " and wall[" + std::to_string(w) + "]");
      if (gap < -tolerance(group) * p.radius_m && !refused_wall) refused_wall = WallOverlap{w, i, gap};
    }
  }
  if (refused != nullptr) {
    const auto a = static_cast<std::size_t>(refused->i);
    const auto b = static_cast<std::size_t>(refused->j);
    std::string more;
    if (refused_count > 1)
      more = " (" + std::to_string(refused_count) + " overlapping pairs in all)";
    throw SceneError(source + ": particles " + std::to_string(a) + " and " +
                     std::to_string(b) + " overlap at start (gap " +
                     format_number(refused->gap_m) + " m, " + allowance(scene, group_of(a, b)) +
                     needed_tolerance(scene, group_of(a, b)) + ")" + more + ": " +
                     describe_particle(scene, origins, a) + "; " + describe_particle(scene, origins, b));
  }
  if (refused_wall) {
    const auto [w, i, gap] = *refused_wall;
    const int group = import_of[i];
    throw SceneError(source + ": particle " + std::to_string(i) + " and wall[" + std::to_string(w) +
                     "] overlap at start (gap " + format_number(gap) +
                     " m; the wall normal points into the domain" +
                     (group < 0 ? "" : "; " + allowance(scene, group) + needed_tolerance(scene, group)) +
                     "): " + describe_particle(scene, origins, i) +
                     generated_overlap_hint(scene, origins[i], w, i));
  }
}

}  // namespace tmdem::coupling
