#include <algorithm>
#include <cmath>
#include <numeric>

#include "coupling/scene/SceneBuilder.h"
#include "coupling/scene/SceneGenerators.h"
#include "coupling/scene/RandomPlacement.h"
#include "mechanics/model/SequentialDeposition.h"

namespace tmdem::coupling {

void SceneBuilder::read_generators() {
  static const std::map<std::string, std::vector<std::string_view>> kind_keys = {
      {"triangular", {"rows", "radius", "origin"}},
      {"column", {"count", "radius", "origin"}},
      {"lattice", {"counts", "spacing", "origin", "radius"}},
      {"random", {"count", "box", "radius", "radii", "fractions"}},
      {"deposit", {"count", "box", "radius", "radii", "fractions"}},
  };
  static const std::vector<std::string_view> common_keys = {
      "kind", "material", "temperature", "fixed_temperature", "heat_source", "fixed"};
  const auto tables = root_.table_array("generate", true);
  deposited_.clear();
  deposit_blocks_.clear();
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
      read_box_filling(tables, index, kind, positions, radii);
      if (kind == "deposit") {
        const auto box = t.optional_table("box", true);
        deposit_blocks_.push_back({index, scene_.particles.size(), positions.size(),
                                   box->required_vec3("min", scene_.dimension),
                                   box->required_vec3("max", scene_.dimension)});
      }
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

namespace {

// The keys of a box filling (kind = "random" or "deposit"), checked.
struct BoxFilling {
  std::int64_t count = 0;
  Vec3 lo{}, hi{};  // m
  std::vector<double> sizes;      // m, radius classes
  std::vector<double> fractions;  // share of each class
};

BoxFilling read_box_filling_keys(const SceneTable& t, int dimension) {
  BoxFilling f;
  f.count = t.required_integer("count", 1, kMaxParticles);
  const auto box = t.optional_table("box", true);
  if (!box) t.missing("box");
  f.lo = box->required_vec3("min", dimension);
  f.hi = box->required_vec3("max", dimension);
  for (int d = 0; d < 3; ++d)
    if (f.hi[d] < f.lo[d])
      box->fail("max", "must be >= min in every component (min = " + format_vec3(f.lo) +
                           ", max = " + format_vec3(f.hi) + ")");
  if (t.has("radius") == t.has("radii"))
    t.fail(t.has("radius") ? "radii" : "radius",
           "give either radius or radii (with fractions), not both and not neither");
  if (t.has("radius")) {
    if (t.has("fractions")) t.fail("fractions", "only allowed with radii, not with radius");
    f.sizes = {t.required_number("radius")};
    f.fractions = {1.0};
  } else {
    f.sizes = t.required_numbers("radii", Range::greater(0.0));
    f.fractions = t.required_numbers("fractions", Range::closed(0.0, 1.0));
    if (f.fractions.size() != f.sizes.size())
      t.fail("fractions", "must have as many entries as radii (" +
                              std::to_string(f.sizes.size()) + "), got " +
                              std::to_string(f.fractions.size()));
    const double sum = std::accumulate(f.fractions.begin(), f.fractions.end(), 0.0);
    if (std::abs(sum - 1.0) > 1e-9)
      t.fail("fractions", "must sum to 1 (within 1e-9), got " + format_number(sum));
  }
  const double largest = *std::max_element(f.sizes.begin(), f.sizes.end());
  for (int d = 0; d < dimension; ++d)
    if (f.hi[d] - f.lo[d] < 2.0 * largest)
      box->fail_here("too small: every extent in the plane of motion must be at least the "
                     "largest diameter " + format_number(2.0 * largest) + " m (min = " +
                     format_vec3(f.lo) + ", max = " + format_vec3(f.hi) + ")");
  return f;
}

}  // namespace

// kind = "random" or "deposit": count, box, and radius or radii + fractions. Particles lie
// entirely inside the box (in 2D only x and y must fit; centres are at z = the middle of the
// box's z range). Radii are given to ids by class in the order of radii (class_radii).
// "random": uniform positions without overlap (place_random); "deposit": dropped one by one
// and rolled to rest on the floor of the box, the face against gravity (deposit_spheres; the
// top of the box bounds the bed's height). Consecutive "deposit" entries with the same box fill
// it together, their particles dropped in one shuffled order (a mixed bed of several materials,
// as a pour of them would give); each keeps its own ids. Reproducible: generator number `index`
// among the [[generate]] entries draws with seed simulation.seed + index (a joint deposit: that
// of its first entry), so two generators differ.
void SceneBuilder::read_box_filling(const std::vector<SceneTable>& tables, std::size_t index,
                                    const std::string& kind, std::vector<Vec3>& positions,
                                    std::vector<double>& radii) {
  const SceneTable& t = tables[index];
  const BoxFilling f = read_box_filling_keys(t, scene_.dimension);
  check_total(t, "count", f.count);
  const auto append = [&](const RandomPlacement& placement) {
    for (std::size_t i = 0; i < placement.positions.size(); ++i) {
      const auto& x = placement.positions[i];
      positions.push_back({x.x(), x.y(), x.z()});
      radii.push_back(placement.radii[i]);
    }
  };
  if (const auto held = deposited_.find(index); held != deposited_.end()) {
    append(held->second);  // laid with an earlier entry of the same box
    deposited_.erase(held);
    return;
  }
  // Keep clear of every particle already in the scene: the [[particle]] entries (read before
  // the generators) and those of earlier generators, so that several generators fill one box
  // around hand-placed particles. [[import]] entries come after and are checked for overlaps.
  RandomPlacement placed;
  for (const auto& p : scene_.particles) {
    placed.positions.emplace_back(p.position_m[0], p.position_m[1], p.position_m[2]);
    placed.radii.push_back(p.radius_m);
  }
  const std::uint64_t seed = scene_.seed + static_cast<std::uint64_t>(index);
  const Eigen::Vector3d box_min(f.lo[0], f.lo[1], f.lo[2]), box_max(f.hi[0], f.hi[1], f.hi[2]);
  if (kind == "random") {
    RandomPlacement placement;
    try {
      placement = place_random(static_cast<std::size_t>(f.count), box_min, box_max, f.sizes,
                               f.fractions, seed, scene_.dimension, placed);
    } catch (const std::exception& error) {
      std::string_view why = error.what();
      for (const std::string_view prefix : {"place_random: ", "random placement: "})
        if (why.starts_with(prefix)) why.remove_prefix(prefix.size());
      t.fail_here("random placement failed: " + std::string(why));
    }
    append(placement);
    return;
  }

  // Gravity along one axis (of the plane of motion in 2D): its direction decides the floor.
  const Vec3& g = scene_.gravity_m_per_s2;
  int axis = -1;
  int along = 0;
  for (int d = 0; d < 3; ++d)
    if (g[d] != 0.0) {
      axis = d;
      ++along;
    }
  if (along != 1 || axis >= scene_.dimension)
    t.fail("kind", "\"deposit\" drops the particles along gravity, which must then be along "
                   "one axis" + std::string(scene_.dimension == 2 ? " (x or y in 2D)" : "") +
                   ": simulation.gravity = " + format_vec3(g));
  // This entry and the next "deposit" entries with the same box: one deposit, split after.
  std::vector<std::size_t> group = {index};
  std::vector<double> all_radii = class_radii(static_cast<std::size_t>(f.count), f.sizes, f.fractions);
  std::vector<std::size_t> group_count = {all_radii.size()};
  std::int64_t total = f.count;
  for (std::size_t j = index + 1; j < tables.size(); ++j) {
    if (tables[j].choice("kind") != "deposit") break;
    const BoxFilling other = read_box_filling_keys(tables[j], scene_.dimension);
    if (other.lo != f.lo || other.hi != f.hi) break;
    total += other.count;
    check_total(tables[j], "count", total);
    const auto more = class_radii(static_cast<std::size_t>(other.count), other.sizes, other.fractions);
    all_radii.insert(all_radii.end(), more.begin(), more.end());
    group.push_back(j);
    group_count.push_back(more.size());
  }
  // Along a periodic axis the deposit fills the period: no faces there, spheres supported
  // across it. The box must say so (its extent there is the period).
  const PeriodicSettings& periodic = scene_.periodic;
  for (int a = 0; a < 3; ++a) {
    if (!periodic.axis[std::size_t(a)]) continue;
    if (f.lo[std::size_t(a)] != periodic.low_m[std::size_t(a)] ||
        f.hi[std::size_t(a)] != periodic.high_m[std::size_t(a)])
      t.fail("box", std::string("along the periodic axis ") + "xyz"[a] +
                        " the box of a deposit must span the period [" +
                        format_number(periodic.low_m[std::size_t(a)]) + ", " +
                        format_number(periodic.high_m[std::size_t(a)]) + "] of [periodic]");
  }
  mechanics::DepositionResult d;
  try {
    d = mechanics::deposit_spheres(all_radii, box_min, box_max, axis, g[axis] < 0.0 ? -1 : 1,
                                   seed, scene_.dimension, placed.positions, placed.radii,
                                   periodic.axis);
  } catch (const std::exception& error) {
    std::string_view why = error.what();
    for (const std::string_view prefix : {"deposit_spheres: ", "SequentialDeposition: "})
      if (why.starts_with(prefix)) why.remove_prefix(prefix.size());
    t.fail("box", "deposition failed: " + std::string(why) +
                      (group.size() > 1 ? " (" + std::to_string(group.size()) +
                                              " [[generate]] entries with this box, filled together)"
                                        : std::string()));
  }
  std::size_t first = 0;
  for (std::size_t k = 0; k < group.size(); ++k) {
    RandomPlacement part;
    part.positions.assign(d.positions.begin() + static_cast<std::ptrdiff_t>(first),
                          d.positions.begin() + static_cast<std::ptrdiff_t>(first + group_count[k]));
    part.radii.assign(all_radii.begin() + static_cast<std::ptrdiff_t>(first),
                      all_radii.begin() + static_cast<std::ptrdiff_t>(first + group_count[k]));
    first += group_count[k];
    if (k == 0)
      append(part);
    else
      deposited_[group[k]] = std::move(part);
  }
}

}  // namespace tmdem::coupling
