#include "coupling/scene/SceneSchema.h"
#include "coupling/scene/SceneSchemaKeys.h"

#include <algorithm>
#include <map>

#include "mechanics/integrator/NscdParameters.h"
#include "coupling/scene/PackingFormats.h"
#include "coupling/scene/SceneProbes.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

namespace {

// Declared here, in this file's own namespace: they hide tmdem::coupling's other number() and value().
using schema_keys::boolean;
using schema_keys::choice;
using schema_keys::concat;
using schema_keys::Key;
using schema_keys::Kind;
using schema_keys::material_reference;
using schema_keys::number;
using schema_keys::particle_settings;
using schema_keys::Range;
using schema_keys::required_number;
using schema_keys::Section;
using schema_keys::settings_sections;
using schema_keys::table;
using schema_keys::value;
using schema_keys::vector3;

// The sections the modes declare, one per section name, keys in declaration order.
std::vector<Section> mode_sections() {
  std::vector<Section> out;
  for (const auto* mode : thermal::heat_transfer_modes()) {
    if (mode->section.empty()) continue;
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const Section& s) { return s.name == mode->section; });
    if (it == out.end()) {
      out.push_back({std::string(mode->section), std::string(mode->section_description), {}});
      it = out.end() - 1;
    }
    for (const auto& p : mode->parameters) {
      if (std::any_of(it->keys.begin(), it->keys.end(), [&](const Key& k) { return k.name == p.key; }))
        continue;
      if (p.boolean) {
        it->keys.push_back(boolean(std::string(p.key), p.default_value != 0.0 ? "true" : "false",
                                   std::string(p.description)));
      } else if (!p.choices.empty()) {
        const std::vector<std::string> names(p.choices.begin(), p.choices.end());
        it->keys.push_back(choice(std::string(p.key), names.at(std::size_t(p.default_value)),
                                  names, std::string(p.description)));
      } else {
        it->keys.push_back(number(std::string(p.key), std::string(p.unit), p.default_value,
                                  p.range, std::string(p.description)));
      }
    }
  }
  return out;
}

std::vector<Section> build_sections() {
  const auto modes = mode_sections();
  const Scene scene_defaults;  // [simulation]'s defaults, written once in Scene.h
  const Material material;     // [[material]]'s, likewise
  std::vector<Key> top{
      value("format", "", "", "\"tmdem-scene-1\"", "scene format version", true),
      table("simulation", Kind::Table, "duration, dimension, gravity, seed", true),
      table("effects", Kind::Table, "what is computed: mechanics and the heat-transfer modes"),
      table("material", Kind::TableArray, "materials, referred to by name", true),
      table("particle", Kind::TableArray, "one particle each"),
      table("generate", Kind::TableArray, "many particles each"),
      table("import", Kind::TableArray,
            "particles from a file: CSV, LAMMPS/LIGGGHTS text dump or a tmdem result"),
      table("assign", Kind::TableArray, "changes selected particles after generation"),
      table("wall", Kind::TableArray, "infinite planes and cylinders"),
      table("periodic", Kind::Table, "periodic boundaries: the axes along which space repeats")};
  for (const auto& s : modes) top.push_back(table(s.name, Kind::Table, s.description));
  for (const auto& k : {table("mechanics", Kind::Table, "NSCD contact dynamics"),
                        table("thermal", Kind::Table, "thermal integrator and contact conductance"),
                        table("output", Kind::Table, "result file, frames, checkpoints")})
    top.push_back(k);
  top.push_back(probe_schema_key());

  std::vector<Key> effects{choice("mechanics", "settle", {"dynamic", "settle", "coupled", "off"},
                                  "\"dynamic\": NSCD every step; \"settle\": NSCD until at rest "
                                  "(before t = 0), then frozen; \"coupled\": settle, then during "
                                  "the heating the packing is settled again every "
                                  "mechanics.coupling_interval with the particles' radii grown "
                                  "by their material's thermal_expansion, and the network "
                                  "follows (docs/thermo-mechanics.md); \"off\": contacts from "
                                  "geometry")};
  for (const auto& e : thermal::heat_transfer_effects())
    effects.push_back(boolean(std::string(e.key), e.default_on ? "true" : "false",
                              std::string(e.description)));

  std::vector<Section> sections{
      {"", "the top level of the file", top},
      {"simulation", "the run",
       {required_number("duration", "s", Range::greater(0.0), "simulated time of the run"),
        value("dimension", "", std::to_string(scene_defaults.dimension), "2 or 3",
              "2: motion in the xy-plane (particles are still spheres)"),
        vector3("gravity", "m/s^2", "[0, 0, 0]", "gravitational acceleration; z = 0 in 2D", false),
        value("seed", "", std::to_string(scene_defaults.seed), "integer >= 0",
              "seed of the random generators ([[generate]] number k draws with seed + k)")}},
      {"effects", "only what is switched on is computed", effects},
      {"material", "one material",
       {value("name", "", "", "non-empty, unique", "name the bodies refer to", true),
        required_number("density", "kg/m^3", Range::greater(0.0), "density"),
        required_number("young_modulus", "Pa", Range::greater(0.0), "Young's modulus"),
        required_number("poisson_ratio", "", Range::open(-1.0, 0.5), "Poisson ratio"),
        number("friction", "", material.friction, Range::at_least(0.0), "Coulomb friction coefficient"),
        number("rolling_friction", "", material.rolling_friction, Range::closed(0.0, 1.0),
               "rolling resistance mu_r: a contact resists rolling with a torque up to "
               "mu_r R_eff N (R_eff = R_i R_j / (R_i + R_j), a wall R_i; the smaller mu_r of the "
               "two materials); 0 rolls freely. Solved by every mechanics.solver"),
        value("conductivity", "W/(m K)", "", "> 0, or [[T_K, k], ...] (T increasing, k > 0)",
              "thermal conductivity; a table: piecewise linear in T, clamped outside it (needs "
              "thermal.integrator cvode or ida with linear_solver klu)", true),
        value("heat_capacity", "J/(kg K)", "", "> 0, or [[T_K, c], ...] (T increasing, c > 0)",
              "specific heat c; a table: piecewise linear in T, clamped outside it, the energy "
              "being m int c dT (cvode or ida with klu)", true),
        number("emissivity", "", material.emissivity, Range::closed(0.0, 1.0), "surface emissivity"),
        number("thermal_expansion", "1/K", material.thermal_expansion_per_K, Range::closed(-1e-3, 1e-3),
               "linear thermal expansion coefficient alpha: with effects.mechanics = \"coupled\" "
               "a particle's radius is r0 (1 + alpha (T - T0)), r0 and T0 its radius and "
               "temperature at the start; mass and moment of inertia are kept; walls do not "
               "expand"),
        number("roughness", "m", material.roughness_m, Range::at_least(0.0),
               "RMS surface roughness sigma, for thermal.conductance = \"bahrami\" (0: smooth; a "
               "pair's sigma is sqrt(sigma1^2 + sigma2^2); docs/heat-modes.md \"Rough contacts\")"),
        number("asperity_slope", "", material.asperity_slope, Range::at_least(0.0),
               "mean absolute slope m of the surface's asperities, for thermal.conductance = "
               "\"bahrami\" (> 0 needed with roughness > 0; a pair's m is sqrt(m1^2 + m2^2))"),
        number("microhardness", "Pa", std::nullopt, Range::greater(0.0),
               "microhardness of the surface layer, for thermal.conductance = \"bahrami\" "
               "(needed with roughness > 0; a pair takes the softer surface's)")}},
      {"particle", "one particle (ids: [[particle]] entries first, then [[generate]])",
       concat({vector3("position", "m", "", "centre"),
               required_number("radius", "m", Range::greater(0.0), "radius"),
               material_reference()},
              particle_settings(true))},
      {"generate", "many particles of one kind",
       concat({choice("kind", "", {"triangular", "column", "lattice", "random", "deposit"},
                      "arrangement; each kind takes only its own keys below. \"random\": "
                      "uniform positions in the box without overlap; \"deposit\": dropped one "
                      "by one along gravity (which must be along an axis) onto the box's floor "
                      "and rolled to rest, a packed bed ready to settle (docs/mechanics.md)"),
               value("rows", "", "", "integers >= 1",
                     "triangular: particles per row, bottom row first, each row centred on the "
                     "one below"),
               value("count", "", "", "integer >= 1", "column, random, deposit: number of particles"),
               value("counts", "", "", "3 integers >= 1 (nz = 1 in 2D)", "lattice: [nx, ny, nz]"),
               number("spacing", "m", std::nullopt, Range::greater(0.0),
                      "lattice: centre distance (>= 2 radius)"),
               number("radius", "m", std::nullopt, Range::greater(0.0),
                      "triangular, column, lattice, random, deposit: radius of every particle"),
               value("radii", "m", "", "numbers > 0",
                     "random, deposit: radius classes (with fractions)"),
               value("fractions", "", "", "numbers in [0, 1], summing to 1",
                     "random, deposit: share of the particles in each radius class"),
               vector3("origin", "m", "",
                       "triangular, column, lattice: centre of the first particle", false),
               table("box", Kind::Table,
                     "random, deposit: box = { min, max } the particles lie in (deposit: its face "
                     "against gravity is the floor, its sides confine the bed, its top bounds "
                     "the bed's height)"),
               material_reference()},
              particle_settings(true))},
      {"box", "a box { min, max } (centres inside, inclusive)",
       {vector3("min", "m", "", "lowest corner"),
        vector3("max", "m", "", "highest corner (>= min)")}},
      {"import",
       "particles from a file, after the [[generate]] entries (ids in file order; rows sorted by "
       "an id column when there is one). Columns by name: x, y, z (or xu, yu, zu; z may be left "
       "out in 2D), radius (or diameter), and optionally material, type, id, temperature, fixed, "
       "fixed_temperature, heat_source; other columns are ignored. temperature, "
       "fixed_temperature, heat_source, fixed and material given here set every imported "
       "particle, overriding the file",
       concat({value("file", "", "", "path of a regular file", "particle file; relative paths "
                     "are relative to the current folder", true),
               choice("format", "auto", packing_format_choices(),
                      "\"csv\": header line then one particle per line; \"lammps\": the last "
                      "snapshot of a text dump (ITEM: ATOMS ...); \"tmdem\": a frame of a "
                      "result file; \"auto\": .csv, .h5/.hdf5, or a dump by its first line"),
               value("type_materials", "", "", "[[material]] names",
                     "material of LAMMPS atom type 1, 2, ... (without material)"),
               value("temperature_column", "", "\"temperature\"", "a column name",
                     "the column holding the temperature in K, e.g. \"f_Temp[0]\" (LIGGGHTS)"),
               number("length_scale", "m", 1.0, Range::greater(0.0),
                      "metres per length unit of the file (positions and radii; 1e-3 for mm)"),
               vector3("offset", "m", "[0, 0, 0]", "added to every position after scaling",
                       false),
               value("frame", "", "-1", "integer; negative counts from the end",
                     "format = \"tmdem\": the frame read (-1: the last complete frame)"),
               number("overlap_tolerance", "", 1.0e-9, Range::closed(0.0, 0.5),
                      "overlap accepted between two particles of this import, and between one "
                      "of them and a wall, as a fraction of the smaller radius (settled packings "
                      "overlap slightly); the largest found is reported, and a file refused names its deepest "
                      "overlap and a tolerance that accepts it"),
               choice("overlaps", "hold", {"hold", "push_out"},
                      "what the mechanics makes of the overlaps accepted: \"hold\": they are the "
                      "packing's (a bed made at a softened modulus, as LIGGGHTS makes them), so the "
                      "position step never pushes them out; each pair's held overlap only shrinks "
                      "(to the pair's overlap after each step) and is gone once the pair opens "
                      "(normal_law = \"rigid\"; a \"hertz\" law reads every overlap as elastic). "
                      "\"push_out\": the position step removes them in the first steps (with 4% of "
                      "a radius the whole bed expands, then resettles: docs/mechanics.md)"),
               value("contacts", "", "", "path of a regular file",
                     "a LAMMPS/LIGGGHTS local dump (ITEM: ENTRIES ...) of the pair contacts "
                     "with their forces in N, the snapshot of the particle dump's timestep (else "
                     "the last); with effects.mechanics = \"off\" the run's contacts are these "
                     "pairs and the walls the particles rest on (wall force from each particle's "
                     "balance), so thermal.conductance = \"hertz\" can be used. Needs an id "
                     "column in the particle file"),
               table("contact_columns", Kind::Table,
                     "the columns of contacts: { id1, id2, normal_force or force }"),
               number("wall_gap", "", 1.0e-3, Range::closed(0.0, 0.5),
                      "with contacts: a particle rests on a wall when its gap to it is at most "
                      "wall_gap x its radius (overlaps included)")},
              concat(particle_settings(false),
                     {value("material", "", "", "a [[material]] name",
                            "material of every imported particle (else the file's material "
                            "column, or its type with type_materials)")}))},
      {"contact_columns",
       "the columns of an [[import]] contacts file, by name (LIGGGHTS `compute pc all "
       "pair/gran/local pos id force`: id1 = \"c_pc[7]\", id2 = \"c_pc[8]\", force = "
       "[\"c_pc[10]\", \"c_pc[11]\", \"c_pc[12]\"])",
       {value("id1", "", "\"id1\"", "a column name", "id of the first particle"),
        value("id2", "", "\"id2\"", "a column name", "id of the second particle"),
        value("normal_force", "N", "\"fn\"", "a column name",
              "the normal force, >= 0 (instead of force)"),
        value("force", "N", "[\"fx\", \"fy\", \"fz\"]", "3 column names",
              "the contact force vector; its normal part |F . n| (n: the unit vector between the "
              "centres) is used. Neither given: fn if the file has it, else fx, fy, fz")}},
      {"assign",
       "changes selected particles: exactly one of ids, box, nearest; at least one setting",
       concat({value("ids", "", "", "integers >= 0, existing ids", "select these particle ids"),
               table("box", Kind::Table, "select the particles whose centre is inside"),
               table("nearest", Kind::Table, "select the count particles nearest to point")},
              concat(particle_settings(false),
                     {value("material", "", "", "a [[material]] name", "new material")}))},
      {"nearest", "nearest = { point, count }",
       {vector3("point", "m", "", "the point distances are measured from"),
        value("count", "", "", "integer in [1, number of particles]", "how many particles", true)}},
      {"wall", "an infinite plane, or an infinite cylinder with the particles inside",
       {choice("shape", "plane", {"plane", "cylinder"},
               "\"plane\": point and normal; \"cylinder\" (3D): point on the axis, axis, radius"),
        vector3("point", "m", "", "a point of the plane (cylinder: a point of the axis)"),
        vector3("normal", "", "", "plane: normal, pointing into the domain (normalised; non-zero)",
                false),
        vector3("axis", "", "", "cylinder: direction of the axis (normalised; non-zero)", false),
        number("radius", "m", std::nullopt, Range::greater(0.0), "cylinder: radius"),
        material_reference(),
        value("temperature", "K", "", "> 0, or [[t_s, T_K], ...] (times increasing)",
              "isothermal wall exchanging heat by contact conduction; a table: piecewise linear "
              "in time, clamped outside it; omitted (and no heat_flux): adiabatic"),
        number("heat_flux", "W/m^2", std::nullopt, Range::any(),
               "imposed heat flux into the bed (negative: out), instead of a temperature; the "
               "power heat_flux x heat_flux_area is shared among the touching particles in "
               "proportion to their contact conductance"),
        number("heat_flux_area", "m^2", std::nullopt, Range::greater(0.0),
               "the area the heat flux is imposed over (with heat_flux)"),
        boolean("piston", "false",
                "plane: the wall moves along its normal under force (or pressure x "
                "pressure_area) plus its weight, as a body of the contact problem; needs "
                "effects.mechanics \"settle\" or \"dynamic\""),
        number("mass", "kg", std::nullopt, Range::greater(0.0), "piston: its mass (required)"),
        number("force", "N", std::nullopt, Range::at_least(0.0),
               "piston: force pushing it into the domain (not with pressure); neither: 0, "
               "its weight only"),
        number("pressure", "Pa", std::nullopt, Range::at_least(0.0),
               "piston: pressure pushing it into the domain, over pressure_area"),
        number("pressure_area", "m^2", std::nullopt, Range::greater(0.0),
               "piston: the area the pressure acts over (e.g. the box cross-section)"),
        choice("start", "point", {"point", "on_bed"},
               "piston: where its plane starts; \"point\": through point; \"on_bed\": resting "
               "on the bed's top, point moved along the normal to the particles' farthest "
               "extent against it (the top of the top sphere), so that it presses from the "
               "first step instead of falling onto the bed")}}};
  sections.push_back(
      {"periodic",
       "periodic boundaries (no key: none): a particle leaving at max comes back at min, pairs "
       "touch through the nearest image; particles outside [min, max) at start are moved in by "
       "whole periods; walls must be planes parallel to every periodic axis; each period at "
       "least 2 x (largest diameter + 0.1 x largest radius)",
       {value("x", "m", "", "[min, max], max > min", "periodic along x with period max - min"),
        value("y", "m", "", "[min, max], max > min", "periodic along y with period max - min"),
        value("z", "m", "", "[min, max], max > min; 3D only",
              "periodic along z with period max - min")}});
  for (const auto& s : modes) sections.push_back(s);
  for (auto& s : settings_sections()) sections.push_back(std::move(s));
  sections.push_back(probe_schema_section());
  return sections;
}

struct Cache {
  std::uint64_t registry_version = ~std::uint64_t{0};
  std::vector<Section> sections;
  std::map<std::string, const std::vector<Key>*, std::less<>> by_name;
};

// Rebuilt when a mode is registered (before any scene is read), so the pointers handed out stay
// valid while scenes are read.
const Cache& cache() {
  static Cache c;
  const auto version = thermal::heat_transfer_registry_version();
  if (c.registry_version != version) {
    c.sections = build_sections();
    c.by_name.clear();
    for (const auto& s : c.sections) c.by_name.emplace(s.name, &s.keys);
    c.registry_version = version;
  }
  return c;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

const std::vector<Section>& SceneSchema::sections() { return cache().sections; }

const std::vector<Key>* SceneSchema::keys(std::string_view schema) {
  const auto& map = cache().by_name;
  const auto it = map.find(schema);
  return it == map.end() ? nullptr : it->second;
}

const Key* SceneSchema::find(std::string_view schema, std::string_view name) {
  const auto* list = keys(schema);
  if (list == nullptr) return nullptr;
  for (const auto& key : *list)
    if (key.name == name) return &key;
  return nullptr;
}

std::string SceneSchema::key_list(std::string_view schema) {
  std::string out;
  if (const auto* list = keys(schema)) {
    for (const auto& key : *list) {
      if (!out.empty()) out += ", ";
      out += key.name;
    }
  }
  return out;
}

std::string_view SceneSchema::suggestion(std::string_view schema, std::string_view name) {
  std::string_view best;
  std::size_t best_distance = 3;
  if (const auto* list = keys(schema)) {
    for (const auto& key : *list) {
      const std::size_t d = edit_distance(name, key.name);
      if (d < best_distance) {
        best_distance = d;
        best = key.name;
      }
    }
  }
  return best;
}

SceneSchema::Key schema_value_key(std::string name, std::string unit, std::string default_text,
                                  std::string allowed, std::string description, bool required) {
  SceneSchema::Key k;
  k.name = std::move(name);
  k.unit = std::move(unit);
  k.default_text = std::move(default_text);
  k.allowed = std::move(allowed);
  k.description = std::move(description);
  k.required = required;
  return k;
}

}  // namespace tmdem::coupling
