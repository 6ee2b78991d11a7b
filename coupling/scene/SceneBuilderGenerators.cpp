#include <algorithm>
#include <cmath>
#include <numeric>

#include "coupling/scene/SceneBuilder.h"
#include "coupling/scene/SceneGenerators.h"
#include "coupling/scene/RandomPlacement.h"

namespace tmdem::coupling {

void SceneBuilder::read_generators() {
  static const std::map<std::string, std::vector<std::string_view>> kind_keys = {
      {"triangular", {"rows", "radius", "origin"}},
      {"column", {"count", "radius", "origin"}},
      {"lattice", {"counts", "spacing", "origin", "radius"}},
      {"random", {"count", "box", "radius", "radii", "fractions"}},
  };
  static const std::vector<std::string_view> common_keys = {
      "kind", "material", "temperature", "fixed_temperature", "heat_source", "fixed"};
  const auto tables = root_.table_array("generate", true);
  for (std::size_t index = 0; index < tables.size(); ++index) {
    const SceneTable& t = tables[index];
    const std::string kind = t.choice("kind");
    if (kind.empty()) t.missing("kind");
    const auto& keys = kind_keys.at(kind);
    for (const auto& [key, value] : *t.table()) {
      const auto name = key.str();
      if (std::find(keys.begin(), keys.end(), name) != keys.end() ||
          std::find(common_keys.begin(), common_keys.end(), name) != common_keys.end())
        continue;
      std::string valid;
      for (const auto k : keys) valid += std::string(k) + ", ";
      for (std::size_t k = 1; k < common_keys.size(); ++k)
        valid += std::string(common_keys[k]) + (k + 1 < common_keys.size() ? ", " : "");
      t.fail(name, "not a key of kind = " + quote_text(kind) + " (keys of " + quote_text(kind) +
                       ": " + valid + ")");
    }
    if (!t.has("material")) t.missing("material");
    const ParticleSettings settings = read_settings_of(t);
    std::vector<Vec3> positions;
    std::vector<double> radii;
    if (kind == "triangular") {
      std::vector<int> rows;
      for (const auto r : t.required_integers("rows", 1, kMaxParticles))
        rows.push_back(static_cast<int>(r));
      const double radius = t.required_number("radius");
      const Vec3 origin = t.required_vec3("origin", scene_.dimension);
      check_total(t, "rows", std::accumulate(rows.begin(), rows.end(), std::int64_t{0}));
      positions = triangular_positions(rows, radius, origin);
      radii.assign(positions.size(), radius);
    } else if (kind == "column") {
      const auto count = t.required_integer("count", 1, kMaxParticles);
      const double radius = t.required_number("radius");
      const Vec3 origin = t.required_vec3("origin", scene_.dimension);
      check_total(t, "count", count);
      positions = column_positions(static_cast<int>(count), radius, origin,
                                   up_direction(scene_.gravity_m_per_s2));
      radii.assign(positions.size(), radius);
    } else if (kind == "lattice") {
      const auto counts = t.required_integers("counts", 1, kMaxParticles);
      if (counts.size() != 3)
        t.fail("counts", "expected 3 integers [nx, ny, nz], got " +
                             std::to_string(counts.size()) + " elements");
      if (scene_.dimension == 2 && counts[2] != 1)
        t.fail("counts", "in 2D (dimension = 2) nz must be 1 (got " +
                             std::to_string(counts[2]) + ")");
      const double spacing = t.required_number("spacing");
      const double radius = t.required_number("radius");
      const Vec3 origin = t.required_vec3("origin", scene_.dimension);
      const double total = static_cast<double>(counts[0]) * static_cast<double>(counts[1]) *
                           static_cast<double>(counts[2]);
      check_total(t, "counts", total > static_cast<double>(kMaxParticles)
                                   ? kMaxParticles + 1
                                   : counts[0] * counts[1] * counts[2]);
      const bool neighbours = counts[0] > 1 || counts[1] > 1 || counts[2] > 1;
      if (neighbours && spacing - 2.0 * radius < -kOverlapTolerance * radius)
        t.fail("spacing", "must be >= 2 * radius = " + format_number(2.0 * radius) +
                              ", neighbours would overlap (got " + format_number(spacing) +
                              ")");
      positions = lattice_positions({static_cast<int>(counts[0]), static_cast<int>(counts[1]),
                                     static_cast<int>(counts[2])},
                                    spacing, origin);
      radii.assign(positions.size(), radius);
    } else {
      read_random(t, index, positions, radii);
    }
    for (std::size_t i = 0; i < positions.size(); ++i)
      add_particle(positions[i], radii[i], settings, t.path(), t);
  }
}

void SceneBuilder::check_total(const SceneTable& t, std::string_view key, std::int64_t count) const {
  if (static_cast<std::int64_t>(scene_.particles.size()) + count > kMaxParticles)
    t.fail(key, "too many particles (at most " + std::to_string(kMaxParticles) +
                    " in a scene)");
}

// kind = "random": count, box, and radius or radii + fractions. Particles lie entirely
// inside the box (in 2D only x and y must fit; centres are at z = the middle of the box's z
// range). Radii are given to ids by class in the order of radii (place_random).
// The placement is reproducible: generator number `index` among the [[generate]] entries
// draws with seed simulation.seed + index, so two random generators differ.
void SceneBuilder::read_random(const SceneTable& t, std::size_t index, std::vector<Vec3>& positions,
                 std::vector<double>& radii) {
  const auto count = t.required_integer("count", 1, kMaxParticles);
  check_total(t, "count", count);
  const auto box = t.optional_table("box", true);
  if (!box) t.missing("box");
  const Vec3 lo = box->required_vec3("min", scene_.dimension);
  const Vec3 hi = box->required_vec3("max", scene_.dimension);
  for (int d = 0; d < 3; ++d)
    if (hi[d] < lo[d])
      box->fail("max", "must be >= min in every component (min = " + format_vec3(lo) +
                           ", max = " + format_vec3(hi) + ")");
  std::vector<double> sizes;
  std::vector<double> fractions;
  if (t.has("radius") == t.has("radii"))
    t.fail(t.has("radius") ? "radii" : "radius",
           "give either radius or radii (with fractions), not both and not neither");
  if (t.has("radius")) {
    if (t.has("fractions")) t.fail("fractions", "only allowed with radii, not with radius");
    sizes = {t.required_number("radius")};
    fractions = {1.0};
  } else {
    sizes = t.required_numbers("radii", Range::greater(0.0));
    fractions = t.required_numbers("fractions", Range::closed(0.0, 1.0));
    if (fractions.size() != sizes.size())
      t.fail("fractions", "must have as many entries as radii (" +
                              std::to_string(sizes.size()) + "), got " +
                              std::to_string(fractions.size()));
    const double sum = std::accumulate(fractions.begin(), fractions.end(), 0.0);
    if (std::abs(sum - 1.0) > 1e-9)
      t.fail("fractions", "must sum to 1 (within 1e-9), got " + format_number(sum));
  }
  const double largest = *std::max_element(sizes.begin(), sizes.end());
  for (int d = 0; d < scene_.dimension; ++d)
    if (hi[d] - lo[d] < 2.0 * largest)
      box->fail_here("too small: every extent in the plane of motion must be at least the "
                     "largest diameter " + format_number(2.0 * largest) + " m (min = " +
                     format_vec3(lo) + ", max = " + format_vec3(hi) + ")");
  // Keep clear of every particle already in the scene: the [[particle]] entries (read before
  // the generators) and those of earlier generators, so that several generators fill one box
  // around hand-placed particles. [[import]] entries come after and are checked for overlaps.
  RandomPlacement placed;
  for (const auto& p : scene_.particles) {
    placed.positions.emplace_back(p.position_m[0], p.position_m[1], p.position_m[2]);
    placed.radii.push_back(p.radius_m);
  }
  RandomPlacement placement;
  try {
    placement = place_random(
        static_cast<std::size_t>(count), Eigen::Vector3d(lo[0], lo[1], lo[2]),
        Eigen::Vector3d(hi[0], hi[1], hi[2]), sizes, fractions,
        scene_.seed + static_cast<std::uint64_t>(index), scene_.dimension, placed);
  } catch (const std::exception& error) {
    std::string_view why = error.what();
    for (const std::string_view prefix : {"place_random: ", "random placement: "})
      if (why.starts_with(prefix)) why.remove_prefix(prefix.size());
    t.fail_here("random placement failed: " + std::string(why));
  }
  for (std::size_t i = 0; i < placement.positions.size(); ++i) {
    const auto& x = placement.positions[i];
    positions.push_back({x.x(), x.y(), x.z()});
    radii.push_back(placement.radii[i]);
  }
}

}  // namespace tmdem::coupling
