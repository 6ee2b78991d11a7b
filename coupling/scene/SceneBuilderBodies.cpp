#include <algorithm>
#include <cmath>

#include "coupling/scene/SceneBuilder.h"
#include "thermal/network/PiecewiseLinearTable.h"

namespace tmdem::coupling {

namespace {

// A material property that is a number > 0, or a table [[T_K, value], ...] with temperatures
// increasing strictly and values > 0 (piecewise linear in T, clamped outside it). Returns the
// number, or the table's first value with the table in `table`.
double read_property(const SceneTable& t, std::string_view key,
                     std::vector<std::array<double, 2>>& table) {
  const toml::node* node = t.node(key);
  if (node == nullptr || !node->is_array())
    return t.required_number(key, thermal::ParameterRange::greater(0.0));
  const auto& rows = *node->as_array();
  if (rows.empty()) t.fail(key, "a table needs at least one [T_K, value] entry");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto* row = rows[k].as_array();
    const auto T_read = row && row->size() == 2 ? (*row)[0].value<double>() : std::nullopt;
    const auto value_read = row && row->size() == 2 ? (*row)[1].value<double>() : std::nullopt;
    const std::string entry = "entry " + std::to_string(k) + ": ";
    if (!T_read || !value_read) t.fail(key, entry + "expected [T_K, value], two numbers");
    const double T = T_read.value_or(0.0), value = value_read.value_or(0.0);
    if (!std::isfinite(T) || !(T > 0.0) || !std::isfinite(value) || !(value > 0.0))
      t.fail(key, entry + "needs a temperature > 0 K and a finite value > 0 (got [" +
                      format_number(T) + ", " + format_number(value) + "])");
    if (k > 0 && !(T > table.back()[0]))
      t.fail(key, entry + "temperatures must increase strictly (" + format_number(T) +
                      " K after " + format_number(table.back()[0]) + " K)");
    table.push_back({T, value});
  }
  return table.front()[1];
}
}  // namespace

void SceneBuilder::read_materials() {
  // Required: name, density, young_modulus, poisson_ratio, conductivity, heat_capacity.
  // Optional (defaults: Material, Scene.h, through the schema): friction, rolling_friction,
  // emissivity, thermal_expansion, the surface of rough contacts: roughness, asperity_slope,
  // microhardness (none).
  const auto tables = root_.table_array("material", true);
  for (const SceneTable& t : tables) {
    Material m;
    m.name = t.required_string("name");
    if (m.name.empty()) t.fail("name", "must not be empty");
    if (const auto it = material_ids_.find(m.name); it != material_ids_.end())
      t.fail("name", "duplicate material name " + quote_text(m.name) + " (also material[" +
                         std::to_string(it->second) + "])");
    m.density_kg_per_m3 = t.required_number("density");
    m.young_modulus_Pa = t.required_number("young_modulus");
    m.poisson_ratio = t.required_number("poisson_ratio");
    m.friction = t.number("friction");
    m.rolling_friction = t.number("rolling_friction");
    m.conductivity_W_per_mK = read_property(t, "conductivity", m.conductivity_table);
    m.heat_capacity_J_per_kgK = read_property(t, "heat_capacity", m.heat_capacity_table);
    m.emissivity = t.number("emissivity");
    m.thermal_expansion_per_K = t.number("thermal_expansion");
    m.roughness_m = t.number("roughness");
    m.asperity_slope = t.number("asperity_slope");
    m.microhardness_Pa = t.optional_number("microhardness").value_or(0.0);
    material_ids_.emplace(m.name, static_cast<int>(scene_.materials.size()));
    scene_.materials.push_back(std::move(m));
  }
}

int SceneBuilder::material_of(const SceneTable& t, std::string_view key) const {
  const std::string name = t.required_string(key);
  if (const auto it = material_ids_.find(name); it != material_ids_.end()) return it->second;
  std::string known;
  for (const auto& m : scene_.materials) known += (known.empty() ? "" : ", ") + quote_text(m.name);
  t.fail(key, "unknown material " + quote_text(name) +
                  (known.empty() ? " (the scene defines no [[material]])"
                                 : " (materials: " + known + ")"));
}

ParticleSettings SceneBuilder::read_settings_of(const SceneTable& t) const {
  ParticleSettings s;
  s.temperature_K = t.optional_number("temperature");
  s.fixed_temperature = t.optional_boolean("fixed_temperature");
  s.heat_source_W = t.optional_number("heat_source");
  s.fixed = t.optional_boolean("fixed");
  if (t.has("material")) s.material = material_of(t, "material");
  return s;
}

void SceneBuilder::add_particle(const Vec3& position, double radius, const ParticleSettings& settings,
                  const std::string& origin, const SceneTable& t) {
  if (static_cast<std::int64_t>(scene_.particles.size()) >= kMaxParticles)
    t.fail_here("too many particles (at most " + std::to_string(kMaxParticles) + ")");
  Particle p;  // Particle's defaults (Scene.h) for what the settings leave out
  p.position_m = position;
  p.radius_m = radius;
  settings.apply_to(p);
  scene_.particles.push_back(p);
  origins_.push_back(origin);
  import_of_.push_back(-1);
}

void SceneBuilder::read_particles() {
  const auto tables = root_.table_array("particle", true);
  for (const SceneTable& t : tables) {
    const Vec3 position = t.required_vec3("position", scene_.dimension);
    const double radius = t.required_number("radius");
    if (!t.has("material")) t.missing("material");
    add_particle(position, radius, read_settings_of(t), t.path(), t);
  }
}

namespace {

// temperature: a number, or [[t_s, T_K], ...] with strictly increasing times; heat_flux with
// heat_flux_area instead of a temperature.
void read_wall_heat(const SceneTable& t, Wall& w) {
  const toml::node* node = t.node("temperature");
  if (node != nullptr && node->is_array()) {
    const auto& rows = *node->as_array();
    if (rows.empty()) t.fail("temperature", "a table needs at least one [t_s, T_K] entry");
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto* row = rows[k].as_array();
      const auto time = row && row->size() == 2 ? (*row)[0].value<double>() : std::nullopt;
      const auto temperature = row && row->size() == 2 ? (*row)[1].value<double>() : std::nullopt;
      const std::string entry = "entry " + std::to_string(k) + ": ";
      if (!time || !temperature)
        t.fail("temperature", entry + "expected [t_s, T_K], two numbers");
      const double t_s = time.value_or(0.0), T_K = temperature.value_or(0.0);
      if (!std::isfinite(t_s) || !std::isfinite(T_K) || !(T_K > 0.0))
        t.fail("temperature", entry + "needs a finite time and a temperature > 0 K");
      if (k > 0 && !(t_s > w.temperature_table.back()[0]))
        t.fail("temperature", entry + "times must increase strictly (" + format_number(t_s) +
                                  " s after " + format_number(w.temperature_table.back()[0]) + " s)");
      w.temperature_table.push_back({t_s, T_K});
    }
    thermal::PiecewiseLinearTable table;
    for (const auto& [time, T] : w.temperature_table) {
      table.x.push_back(time);
      table.y.push_back(T);
    }
    w.temperature_K = table(0.0);
  } else {
    w.temperature_K = t.optional_number("temperature", thermal::ParameterRange::greater(0.0));
  }
  w.heat_flux_W_per_m2 = t.optional_number("heat_flux");
  const auto area = t.optional_number("heat_flux_area");
  if (w.heat_flux_W_per_m2 && w.temperature_K)
    t.fail("heat_flux", "a wall has a temperature or a heat flux, not both");
  if (w.heat_flux_W_per_m2.has_value() != area.has_value())
    t.fail(area ? "heat_flux_area" : "heat_flux", "heat_flux and heat_flux_area go together");
  w.heat_flux_area_m2 = area.value_or(0.0);
}

// piston = true and its keys (mass; force, or pressure with pressure_area).
void read_piston(const SceneTable& t, Wall& w) {
  w.piston = t.boolean("piston", false);
  if (!w.piston) {
    for (const char* key : {"mass", "force", "pressure", "pressure_area", "start"})
      if (t.has(key)) t.fail(key, "only a piston = true wall takes this key");
    return;
  }
  w.piston_start_on_bed = t.choice("start") == "on_bed";
  if (w.cylinder) t.fail("piston", "a piston must be a plane wall (shape = \"plane\")");
  w.piston_mass_kg = t.required_number("mass");
  const auto force = t.optional_number("force");
  w.piston_pressure_Pa = t.optional_number("pressure");
  const auto area = t.optional_number("pressure_area");
  if (force && w.piston_pressure_Pa) t.fail("force", "a piston has a force or a pressure, not both");
  if (w.piston_pressure_Pa.has_value() != area.has_value())
    t.fail(area ? "pressure_area" : "pressure", "pressure and pressure_area go together");
  w.piston_area_m2 = area.value_or(0.0);
  w.piston_force_N = force ? *force : w.piston_pressure_Pa.value_or(0.0) * w.piston_area_m2;
}

}  // namespace

void SceneBuilder::read_walls() {
  const auto tables = root_.table_array("wall", true);
  for (const SceneTable& t : tables) {
    Wall w;
    w.point_m = t.required_vec3("point", scene_.dimension);
    w.cylinder = t.has("shape") && t.choice("shape") == "cylinder";
    if (w.cylinder) {
      if (scene_.dimension != 3) t.fail("shape", "a cylinder wall needs simulation.dimension = 3");
      if (t.has("normal")) t.fail("normal", "a cylinder has an axis, not a normal");
      w.radius_m = t.required_number("radius");
    } else {
      for (const char* key : {"axis", "radius"})
        if (t.has(key)) t.fail(key, "only a shape = \"cylinder\" wall takes this key");
    }
    const Vec3 n = t.required_vec3(w.cylinder ? "axis" : "normal", scene_.dimension);
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0.0) || !std::isfinite(length))
      t.fail(w.cylinder ? "axis" : "normal", "must be a non-zero vector (got " + format_vec3(n) + ")");
    w.normal = {n[0] / length, n[1] / length, n[2] / length};
    w.material = material_of(t, "material");
    read_wall_heat(t, w);
    read_piston(t, w);
    // Only the contact mechanics moves a piston: without it, it would silently stand still.
    if (w.piston && scene_.effects.mechanics == MechanicsMode::Off)
      t.fail("piston", "a piston needs effects.mechanics = \"settle\" or \"dynamic\" (the "
                       "contact mechanics moves it); with \"off\" it would stand still: set "
                       "piston = false");
    if (w.piston_start_on_bed) place_on_bed(w);
    scene_.walls.push_back(w);
  }
}

// Moves a plane's point along its normal until the plane touches the particle that reaches
// farthest against the normal: the least of signed distance - radius over the particles is
// 0 (the top of the top sphere for a piston pressing down). The particles are all read by
// now ([[particle]], [[generate]], [[import]]); wrapping into the periods later moves them
// only across the normal (walls are parallel to every periodic axis).
void SceneBuilder::place_on_bed(Wall& w) const {
  double gap_m = INFINITY;
  for (const auto& p : scene_.particles)
    gap_m = std::min(gap_m, wall_signed_distance(w, p.position_m) - p.radius_m);
  for (std::size_t k = 0; k < 3; ++k) w.point_m[k] += gap_m * w.normal[k];
}

void SceneBuilder::read_assigns() {
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

}  // namespace tmdem::coupling
