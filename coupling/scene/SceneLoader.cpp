#include "coupling/scene/SceneLoader.h"
#include "coupling/scene/SceneLimits.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "coupling/scene/SceneGenerators.h"
#include "coupling/scene/SceneOverrides.h"
#include "coupling/scene/SceneTable.h"
#include "coupling/scene/TomlWriter.h"
#include "mechanics/ContactSolverRegistry.h"
#include "mechanics/ParticleSet.h"
#include "mechanics/RandomPlacement.h"
#include "mechanics/TouchingPairs.h"

namespace tmdem::coupling {

namespace {

constexpr std::string_view kFormat = "tmdem-scene-1";
constexpr double kDefaultTemperature_K = 293.15;  // particles without a temperature
constexpr double kDefaultFriction = 0.3;          // [[material]] friction when omitted
constexpr double kDefaultEmissivity = 0.0;        // [[material]] emissivity when omitted
constexpr double kOverlapTolerance = 1e-9;        // of the smaller radius (contract section 2)
constexpr std::int64_t kMaxParticles = 10'000'000;  // sanity bound on generated counts
constexpr std::int64_t kIntMax = std::numeric_limits<std::int64_t>::max();

std::string format_vec3(const Vec3& v) {
  return "[" + format_number(v[0]) + ", " + format_number(v[1]) + ", " + format_number(v[2]) + "]";
}

// Per-particle settings shared by [[particle]], [[generate]] and [[assign]].
struct ParticleSettings {
  std::optional<double> temperature_K;
  std::optional<bool> fixed_temperature;
  std::optional<double> heat_source_W;
  std::optional<bool> fixed;
  std::optional<int> material;

  bool any() const {
    return temperature_K || fixed_temperature || heat_source_W || fixed || material;
  }
  void apply_to(Particle& p) const {
    if (temperature_K) p.temperature_K = *temperature_K;
    if (fixed_temperature) p.fixed_temperature = *fixed_temperature;
    if (heat_source_W) p.heat_source_W = *heat_source_W;
    if (fixed) p.fixed = *fixed;
    if (material) p.material = *material;
  }
};

class SceneBuilder {
 public:
  SceneBuilder(const toml::table& root, std::string source)
      : root_(&root, "", "", source), source_(std::move(source)) {}

  Scene build() {
    root_.check_keys();
    read_format();
    read_simulation();
    read_effects();
    read_materials();
    read_particles();
    read_generators();
    if (scene_.particles.empty())
      throw SceneError(source_ +
                       ": the scene has no particles (add [[particle]] or [[generate]] entries)");
    read_walls();
    read_assigns();
    read_settings();
    check_scene_limits(scene_, origins_, source_);
    check_overlaps();
    return std::move(scene_);
  }

 private:
  void read_format() {
    const auto format = root_.optional_string("format");
    if (!format)
      root_.fail("format", "required key is missing (must be " + quote_text(kFormat) + ")");
    if (*format != kFormat)
      root_.fail("format", "must be " + quote_text(kFormat) + " (got " + quote_text(*format) + ")");
  }

  SceneTable section(std::string_view key, bool enforce) const {
    if (auto table = root_.optional_table(key, enforce)) return *table;
    return SceneTable(nullptr, std::string(key), key, source_, enforce);
  }

  void read_simulation() {
    const SceneTable t = section("simulation", true);
    if (!t.present()) t.fail("duration", "required key is missing (no [simulation] table)");
    scene_.duration_s = t.required_number("duration", Range::greater(0.0));
    scene_.dimension = static_cast<int>(t.integer("dimension", 3, 2, 3));
    scene_.gravity_m_per_s2 = t.optional_vec3("gravity", scene_.dimension).value_or(Vec3{});
    if (scene_.dimension == 2 && scene_.gravity_m_per_s2[2] != 0.0)
      t.fail("gravity", "in 2D (dimension = 2) motion is in the xy-plane: the z component must "
                        "be 0 (got " + format_vec3(scene_.gravity_m_per_s2) + ")");
    scene_.seed = static_cast<std::uint64_t>(t.integer("seed", 1, 0, kIntMax));
  }

  void read_effects() {
    const SceneTable t = section("effects", true);
    const std::string mechanics = t.choice("mechanics", "settle", {"dynamic", "settle", "off"});
    scene_.effects.mechanics = mechanics == "dynamic"  ? MechanicsMode::Dynamic
                               : mechanics == "settle" ? MechanicsMode::Settle
                                                       : MechanicsMode::Off;
    scene_.effects.conduction = t.boolean("conduction", true);
    scene_.effects.convection = t.boolean("convection", false);
    scene_.effects.radiation = t.boolean("radiation", false);
  }

  void read_materials() {
    // Required: name, density, young_modulus, poisson_ratio, conductivity, heat_capacity.
    // Optional: friction (default 0.3), emissivity (default 0.0).
    const auto tables = root_.table_array("material", true);
    for (const SceneTable& t : tables) {
      Material m;
      m.name = t.required_string("name");
      if (m.name.empty()) t.fail("name", "must not be empty");
      if (const auto it = material_ids_.find(m.name); it != material_ids_.end())
        t.fail("name", "duplicate material name " + quote_text(m.name) + " (also material[" +
                           std::to_string(it->second) + "])");
      m.density_kg_per_m3 = t.required_number("density", Range::greater(0.0));
      m.young_modulus_Pa = t.required_number("young_modulus", Range::greater(0.0));
      m.poisson_ratio = t.required_number("poisson_ratio", Range::open(-1.0, 0.5));
      m.friction = t.number("friction", kDefaultFriction, Range::at_least(0.0));
      m.conductivity_W_per_mK = t.required_number("conductivity", Range::greater(0.0));
      m.heat_capacity_J_per_kgK = t.required_number("heat_capacity", Range::greater(0.0));
      m.emissivity = t.number("emissivity", kDefaultEmissivity, Range::closed(0.0, 1.0));
      material_ids_.emplace(m.name, static_cast<int>(scene_.materials.size()));
      scene_.materials.push_back(std::move(m));
    }
  }

  int material_of(const SceneTable& t, std::string_view key) const {
    const std::string name = t.required_string(key);
    if (const auto it = material_ids_.find(name); it != material_ids_.end()) return it->second;
    std::string known;
    for (const auto& m : scene_.materials) known += (known.empty() ? "" : ", ") + quote_text(m.name);
    t.fail(key, "unknown material " + quote_text(name) +
                    (known.empty() ? " (the scene defines no [[material]])"
                                   : " (materials: " + known + ")"));
  }

  ParticleSettings read_settings_of(const SceneTable& t) const {
    ParticleSettings s;
    s.temperature_K = t.optional_number("temperature", Range::greater(0.0));
    s.fixed_temperature = t.optional_boolean("fixed_temperature");
    s.heat_source_W = t.optional_number("heat_source");
    s.fixed = t.optional_boolean("fixed");
    if (t.has("material")) s.material = material_of(t, "material");
    return s;
  }

  void add_particle(const Vec3& position, double radius, const ParticleSettings& settings,
                    const std::string& origin, const SceneTable& t) {
    if (static_cast<std::int64_t>(scene_.particles.size()) >= kMaxParticles)
      t.fail_here("too many particles (at most " + std::to_string(kMaxParticles) + ")");
    Particle p;
    p.position_m = position;
    p.radius_m = radius;
    p.temperature_K = kDefaultTemperature_K;
    settings.apply_to(p);
    scene_.particles.push_back(p);
    origins_.push_back(origin);
  }

  void read_particles() {
    const auto tables = root_.table_array("particle", true);
    for (const SceneTable& t : tables) {
      const Vec3 position = t.required_vec3("position", scene_.dimension);
      const double radius = t.required_number("radius", Range::greater(0.0));
      if (!t.has("material")) t.missing("material");
      add_particle(position, radius, read_settings_of(t), t.path(), t);
    }
  }

  void read_generators() {
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
      const std::string kind = t.choice("kind", "", {"triangular", "column", "lattice", "random"});
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
        const double radius = t.required_number("radius", Range::greater(0.0));
        const Vec3 origin = t.required_vec3("origin", scene_.dimension);
        check_total(t, "rows", std::accumulate(rows.begin(), rows.end(), std::int64_t{0}));
        positions = triangular_positions(rows, radius, origin);
        radii.assign(positions.size(), radius);
      } else if (kind == "column") {
        const auto count = t.required_integer("count", 1, kMaxParticles);
        const double radius = t.required_number("radius", Range::greater(0.0));
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
        const double spacing = t.required_number("spacing", Range::greater(0.0));
        const double radius = t.required_number("radius", Range::greater(0.0));
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

  void check_total(const SceneTable& t, std::string_view key, std::int64_t count) const {
    if (static_cast<std::int64_t>(scene_.particles.size()) + count > kMaxParticles)
      t.fail(key, "too many particles (at most " + std::to_string(kMaxParticles) +
                      " in a scene)");
  }

  // kind = "random": count, box, and radius or radii + fractions. Particles lie entirely
  // inside the box (in 2D only x and y must fit; centres are at z = the middle of the box's z
  // range). Radii are given to ids by class in the order of radii (mechanics::place_random).
  // The placement is reproducible: generator number `index` among the [[generate]] entries
  // draws with seed simulation.seed + index, so two random generators differ.
  void read_random(const SceneTable& t, std::size_t index, std::vector<Vec3>& positions,
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
      sizes = {t.required_number("radius", Range::greater(0.0))};
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
    mechanics::RandomPlacement placement;
    try {
      placement = mechanics::place_random(
          static_cast<std::size_t>(count), Eigen::Vector3d(lo[0], lo[1], lo[2]),
          Eigen::Vector3d(hi[0], hi[1], hi[2]), sizes, fractions,
          scene_.seed + static_cast<std::uint64_t>(index), scene_.dimension);
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

  void read_walls() {
    const auto tables = root_.table_array("wall", true);
    for (const SceneTable& t : tables) {
      Wall w;
      w.point_m = t.required_vec3("point", scene_.dimension);
      const Vec3 n = t.required_vec3("normal", scene_.dimension);
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(length > 0.0) || !std::isfinite(length))
        t.fail("normal", "must be a non-zero vector (got " + format_vec3(n) + ")");
      w.normal = {n[0] / length, n[1] / length, n[2] / length};
      w.material = material_of(t, "material");
      w.temperature_K = t.optional_number("temperature", Range::greater(0.0));
      scene_.walls.push_back(w);
    }
  }

  void read_assigns() {
    const auto tables = root_.table_array("assign", true);
    const std::int64_t n = static_cast<std::int64_t>(scene_.particles.size());
    for (const SceneTable& t : tables) {
      const int selectors = int(t.has("ids")) + int(t.has("box")) + int(t.has("nearest"));
      if (selectors != 1)
        t.fail_here("give exactly one selector: ids, box or nearest (got " +
                    std::to_string(selectors) + ")");
      std::vector<std::size_t> selected;
      if (t.has("ids")) {
        const auto ids = t.required_integers("ids", 0, kIntMax);
        const auto* array = t.node("ids")->as_array();
        for (std::size_t i = 0; i < ids.size(); ++i) {
          if (ids[i] >= n)
            t.fail_at(array->get(i), t.key_path("ids") + "[" + std::to_string(i) + "]",
                      "particle id " + std::to_string(ids[i]) + " does not exist (the scene has " +
                          std::to_string(n) + " particles, ids 0 to " + std::to_string(n - 1) +
                          ")");
          selected.push_back(static_cast<std::size_t>(ids[i]));
        }
      } else if (t.has("box")) {
        const auto box = t.optional_table("box", true);
        const Vec3 lo = box->required_vec3("min", scene_.dimension);
        const Vec3 hi = box->required_vec3("max", scene_.dimension);
        const int dims = scene_.dimension;  // in 2D the z range is ignored
        for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
          const Vec3& x = scene_.particles[i].position_m;
          bool inside = true;
          for (int d = 0; d < dims; ++d) inside = inside && x[d] >= lo[d] && x[d] <= hi[d];
          if (inside) selected.push_back(i);
        }
        if (selected.empty())
          t.fail("box", "selects no particle (min = " + format_vec3(lo) + ", max = " +
                            format_vec3(hi) + "; a particle is selected when its centre is "
                            "inside)");
      } else {
        const auto nearest = t.optional_table("nearest", true);
        const Vec3 point = nearest->required_vec3("point", scene_.dimension);
        const auto count = nearest->required_integer("count", 1, kIntMax);
        if (count > n)
          nearest->fail("count", "must be at most the number of particles, " + std::to_string(n) +
                                     " (got " + std::to_string(count) + ")");
        const int dims = scene_.dimension;  // in 2D distances are measured in the xy-plane
        std::vector<std::pair<double, std::size_t>> order;
        order.reserve(scene_.particles.size());
        for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
          const Vec3& x = scene_.particles[i].position_m;
          double d2 = 0.0;
          for (int d = 0; d < dims; ++d) d2 += (x[d] - point[d]) * (x[d] - point[d]);
          order.emplace_back(d2, i);
        }
        std::partial_sort(order.begin(), order.begin() + count, order.end());
        for (std::int64_t k = 0; k < count; ++k) selected.push_back(order[std::size_t(k)].second);
      }
      const ParticleSettings settings = read_settings_of(t);
      if (!settings.any())
        t.fail_here("sets nothing: give any of temperature, fixed_temperature, heat_source, "
                    "fixed, material");
      for (const std::size_t i : selected) settings.apply_to(scene_.particles[i]);
    }
  }

  void read_settings() {
    const bool mechanics_on = scene_.effects.mechanics != MechanicsMode::Off;
    {
      const SceneTable t = section("convection", scene_.effects.convection);
      auto& c = scene_.convection;
      c.coefficient_W_per_m2K =
          t.number("coefficient", c.coefficient_W_per_m2K, Range::at_least(0.0));
      c.fluid_temperature_K =
          t.number("fluid_temperature", c.fluid_temperature_K, Range::greater(0.0));
    }
    {
      const SceneTable t = section("radiation", scene_.effects.radiation);
      auto& r = scene_.radiation;
      r.ambient_temperature_K =
          t.number("ambient_temperature", r.ambient_temperature_K, Range::at_least(0.0));
    }
    {
      const SceneTable t = section("mechanics", mechanics_on);
      auto& m = scene_.mechanics;
      m.time_step_s = t.number("time_step", m.time_step_s, Range::greater(0.0));
      m.theta = t.number("theta", m.theta, Range::open_closed(0.0, 1.0));
      m.solver = t.choice("solver", m.solver, mechanics::contact_solver_names());
      m.tolerance = t.number("tolerance", m.tolerance, Range::greater(0.0));
      const auto iterations = t.integer("max_iterations", m.max_iterations,
                                        mechanics_on ? 1 : std::numeric_limits<int>::min(),
                                        std::numeric_limits<int>::max());
      m.max_iterations = static_cast<int>(iterations);
      m.settle_time_s = t.number("settle_time", m.settle_time_s, Range::greater(0.0));
      m.settle_velocity_m_per_s =
          t.number("settle_velocity", m.settle_velocity_m_per_s, Range::greater(0.0));
    }
    {
      const SceneTable t = section("thermal", true);
      auto& th = scene_.thermal;
      th.integrator = t.choice("integrator", th.integrator, {"cvode", "ida", "explicit"});
      th.linear_solver = t.choice("linear_solver", th.linear_solver, {"klu", "pcg"});
      th.relative_tolerance =
          t.number("relative_tolerance", th.relative_tolerance, Range::greater(0.0));
      th.absolute_tolerance_K =
          t.number("absolute_tolerance", th.absolute_tolerance_K, Range::greater(0.0));
      th.explicit_step_s = t.number("explicit_step", th.explicit_step_s, Range::at_least(0.0));
      th.conductance = t.choice("conductance", th.conductance, {"hertz", "constant"});
      th.constant_conductance_W_per_K = t.number(
          "constant_conductance", th.constant_conductance_W_per_K, Range::greater(0.0));
      th.coupling = t.choice("coupling", th.coupling, {"continue", "restart"});
      if (scene_.effects.conduction && !mechanics_on && th.conductance == "hertz") {
        if (t.has("conductance"))
          t.fail("conductance",
                 "\"hertz\" needs contact forces but effects.mechanics = \"off\"; use "
                 "conductance = \"constant\" or mechanics = \"settle\" or \"dynamic\"");
        const SceneTable effects = section("effects", true);
        effects.fail("mechanics",
                     "\"off\" leaves no contact forces for thermal.conductance = \"hertz\" "
                     "(the default); set thermal.conductance = \"constant\"");
      }
    }
    {
      const SceneTable t = section("output", true);
      auto& o = scene_.output;
      o.file = t.optional_string("file").value_or(o.file);
      if (o.file.empty()) t.fail("file", "must not be empty");
      o.interval_s = t.number("interval", o.interval_s, Range::greater(0.0));
      o.contacts = t.boolean("contacts", o.contacts);
      o.checkpoint_interval_s =
          t.number("checkpoint_interval", o.checkpoint_interval_s, Range::at_least(0.0));
    }
  }

  std::string describe_particle(std::size_t i) const {
    const Particle& p = scene_.particles[i];
    return "particle " + std::to_string(i) + " from " + origins_[i] + " at " +
           format_vec3(p.position_m) + " with radius " + format_number(p.radius_m);
  }

  void check_overlaps() const {
    mechanics::ParticleSet set;
    set.reserve(scene_.particles.size());
    for (const auto& p : scene_.particles) {
      const double mass = mechanics::sphere_mass(
          p.radius_m, scene_.materials[static_cast<std::size_t>(p.material)].density_kg_per_m3);
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
      throw SceneError(source_ + ": particles " + std::to_string(a) + " and " +
                       std::to_string(b) + " overlap at start (gap " +
                       format_number(overlaps.front().gap_m) +
                       " m, allowed down to -1e-9 x the smaller radius)" + more + ": " +
                       describe_particle(a) + "; " + describe_particle(b));
    }
    for (std::size_t w = 0; w < scene_.walls.size(); ++w) {
      const Wall& wall = scene_.walls[w];
      for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
        const Particle& p = scene_.particles[i];
        double distance = 0.0;
        for (int d = 0; d < 3; ++d) distance += (p.position_m[d] - wall.point_m[d]) * wall.normal[d];
        const double gap = distance - p.radius_m;
        if (gap < -kOverlapTolerance * p.radius_m)
          throw SceneError(source_ + ": particle " + std::to_string(i) + " and wall[" +
                           std::to_string(w) + "] overlap at start (gap " + format_number(gap) +
                           " m; the wall normal points into the domain): " +
                           describe_particle(i));
      }
    }
  }

  SceneTable root_;
  std::string source_;
  Scene scene_;
  std::vector<std::string> origins_;  // per particle: "particle[3]" or "generate[0]"
  std::map<std::string, int> material_ids_;
};

}  // namespace

Scene load_scene_text(std::string_view toml_text, std::string_view source_name,
                      const std::vector<std::string>& set_overrides) {
  const std::string source(source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw SceneError(source + ":" + std::to_string(begin.line) + ":" +
                     std::to_string(begin.column) +
                     ": TOML syntax error: " + std::string(error.description()));
  }
  apply_set_overrides(root, set_overrides);
  Scene scene = SceneBuilder(root, source).build();
  scene.resolved_toml = write_toml(root);
  scene.source = source;
  return scene;
}

Scene load_scene_file(const std::string& path, const std::vector<std::string>& set_overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError("cannot open scene file " + quote_text(path) + ": it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError("cannot open scene file " + quote_text(path) + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError("cannot read scene file " + quote_text(path));
  return load_scene_text(text.str(), path, set_overrides);
}

}  // namespace tmdem::coupling
