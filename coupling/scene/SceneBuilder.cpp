#include "coupling/scene/SceneBuilder.h"

#include "coupling/common/ShortestNumber.h"
#include "coupling/scene/HeatModes.h"
#include "coupling/scene/SceneLimits.h"
#include "coupling/scene/SceneProbes.h"
#include "coupling/scene/SceneValidation.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

namespace {
constexpr std::string_view kFormat = "tmdem-scene-1";
}  // namespace

std::string format_vec3(const Vec3& v) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  std::string out = "[";
  for (int d = 0; d < 3; ++d) {
    if (d > 0) out += ", ";
    out += format_number(v[d]);
  }
  out += "]";
  return out;
}

Scene SceneBuilder::build() {
  root_.check_keys();
  read_format();
  read_simulation();
  read_periodic();
  read_effects();
  read_materials();
  read_particles();
  read_generators();
  read_imports();
  if (scene_.particles.empty())
    throw SceneError(source_ +
                     ": the scene has no particles (add [[particle]], [[generate]] or [[import]] entries)");
  read_walls();
  check_periodic_bodies();
  read_assigns();
  read_heat_modes();
  read_settings();
  scene_.probes = read_probes(root_, scene_.dimension);
  check_scene_limits(scene_, origins_, source_);
  check_overlaps(scene_, origins_, import_of_, source_);
  scene_.warnings = unsupported_deposit_warnings(scene_, deposit_blocks_);
  if (std::string output = large_output_warning(scene_); !output.empty())
    scene_.warnings.push_back(std::move(output));
  // Growth under rigid contacts: a confined bed has no solution (docs/thermo-mechanics.md).
  if (scene_.effects.mechanics == MechanicsMode::Coupled &&
      scene_.mechanics.normal_law == mechanics::NormalLaw::rigid)
    for (const auto& m : scene_.materials)
      if (m.thermal_expansion_per_K != 0.0) {
        scene_.warnings.push_back(
            "material " + quote_text(m.name) + " expands (thermal_expansion " +
            shortest_number(m.thermal_expansion_per_K) +
            " 1/K) under mechanics.normal_law = \"rigid\": rigid contacts carry no thermal "
            "stress and a confined bed has no solution as its particles grow; use "
            "mechanics.normal_law = \"hertz\"");
        break;
      }
  return std::move(scene_);
}

void SceneBuilder::read_format() {
  const auto format = root_.optional_string("format");
  if (!format)
    root_.fail("format", "required key is missing (must be " + quote_text(kFormat) + ")");
  if (*format != kFormat)
    root_.fail("format", "must be " + quote_text(kFormat) + " (got " + quote_text(*format) + ")");
}

SceneTable SceneBuilder::section(std::string_view key, bool enforce) const {
  if (auto table = root_.optional_table(key, enforce)) return *table;
  return SceneTable(nullptr, std::string(key), key, source_, enforce);
}

void SceneBuilder::read_simulation() {
  const SceneTable t = section("simulation", true);
  if (!t.present()) t.fail("duration", "required key is missing (no [simulation] table)");
  scene_.duration_s = t.required_number("duration");
  scene_.dimension = static_cast<int>(t.integer("dimension", scene_.dimension, 2, 3));
  scene_.gravity_m_per_s2 = t.optional_vec3("gravity", scene_.dimension).value_or(Vec3{});
  if (scene_.dimension == 2 && scene_.gravity_m_per_s2[2] != 0.0)
    t.fail("gravity", "in 2D (dimension = 2) motion is in the xy-plane: the z component must "
                      "be 0 (got " + format_vec3(scene_.gravity_m_per_s2) + ")");
  scene_.seed = static_cast<std::uint64_t>(
      t.integer("seed", std::int64_t(scene_.seed), 0, kIntMax));  // Scene's defaults
}

void SceneBuilder::read_effects() {
  const SceneTable t = section("effects", true);
  const std::string mechanics = t.choice("mechanics");
  scene_.effects.mechanics = mechanics == "dynamic"   ? MechanicsMode::Dynamic
                             : mechanics == "settle"  ? MechanicsMode::Settle
                             : mechanics == "coupled" ? MechanicsMode::Coupled
                                                      : MechanicsMode::Off;
  // The heat-transfer modes' switches, as each mode declares them.
  for (const auto& e : thermal::heat_transfer_effects())
    scene_.effects.heat[std::string(e.key)] = t.boolean(e.key, e.default_on);
  // A mode fed by the contacts' dissipation needs contacts that move during the run.
  for (const auto* mode : thermal::heat_transfer_modes())
    if (mode->uses_contact_dissipation && !mode->effect.empty() &&
        switched_on(scene_.effects, *mode) && scene_.effects.mechanics != MechanicsMode::Dynamic)
      t.fail(mode->effect, "needs effects.mechanics = \"dynamic\" (heat from contacts that "
                           "move during the run; mechanics is \"" + mechanics + "\")");
}

// Every registered mode reads its own section by its own declaration: ranges (and the mode's own
// check) apply only when its effect is on; unknown keys and types are refused always.
void SceneBuilder::read_heat_modes() {
  for (const auto* mode : thermal::heat_transfer_modes()) {
    if (mode->section.empty()) continue;
    const bool on = switched_on(scene_.effects, *mode);
    const SceneTable t = section(mode->section, on);
    std::vector<double> values;
    for (const auto& p : mode->parameters) {
      if (p.boolean) {
        values.push_back(t.boolean(p.key, p.default_value != 0.0) ? 1.0 : 0.0);
      } else if (!p.choices.empty()) {
        const std::string name = t.choice(p.key);  // refuses an unknown name, listing the valid
        std::size_t index = 0;
        while (index < p.choices.size() && p.choices[index] != name) ++index;
        values.push_back(double(index));
      } else {
        values.push_back(t.number(p.key, p.default_value, p.range));
      }
      scene_.heat_modes.set(mode->name, p.key, values.back());
    }
    if (on && mode->check)
      if (const auto problem = mode->check(thermal::ModeParameters(*mode, std::move(values))))
        t.fail(problem->key, problem->problem);
  }
}

// Defaults, ranges and choices of these sections are the schema's (SceneSchema.cpp), so the
// scene reference shows exactly what is checked here.
// thermal.conductance = "bahrami": every conductivity constant (the law has no k(T) form), and
// every rough surface with the slope and microhardness its micro-contacts need.
void SceneBuilder::check_rough_surfaces(const SceneTable& thermal_table) const {
  const auto tables = root_.table_array("material", true);
  for (std::size_t k = 0; k < scene_.materials.size() && k < tables.size(); ++k) {
    const Material& m = scene_.materials[k];
    if (!m.conductivity_table.empty())
      thermal_table.fail("conductance",
                         "\"bahrami\" needs constant conductivities, but material \"" + m.name +
                             "\" gives its conductivity as a table; set a constant or "
                             "conductance = \"hertz\"");
    if (!(m.roughness_m > 0.0)) continue;
    const std::string why = " (roughness " + format_number(m.roughness_m) +
                            " m with thermal.conductance = \"bahrami\")";
    if (!(m.asperity_slope > 0.0))
      tables[k].fail("asperity_slope", "must be given and > 0 for a rough surface" + why);
    if (!(m.microhardness_Pa > 0.0))
      tables[k].fail("microhardness", "must be given for a rough surface" + why);
  }
}

void SceneBuilder::read_settings() {
  const bool mechanics_on = scene_.effects.mechanics != MechanicsMode::Off;
  {
    const SceneTable t = section("mechanics", mechanics_on);
    auto& m = scene_.mechanics;
    m.time_step_s = t.number("time_step");
    m.theta = t.number("theta");
    m.solver = t.choice("solver");
    m.stop_test = t.choice("stop_test");
    m.normal_law = mechanics::parse_normal_law(t.choice("normal_law"));
    m.tolerance = t.number("tolerance");
    m.fall_tolerance = t.number("fall_tolerance");
    m.fall_speed_m_per_s = t.optional_number("fall_speed").value_or(0.0);  // absent: automatic
    m.fall_share = t.number("fall_share");
    m.stop_travel = t.number("stop_travel");
    m.skip_out_of_reach = t.boolean("skip_out_of_reach", m.skip_out_of_reach);
    m.estimate_piston_reach = t.boolean("estimate_piston_reach", m.estimate_piston_reach);
    m.static_warm_start = t.boolean("static_warm_start", m.static_warm_start);
    m.residual_check_every = static_cast<int>(t.integer("residual_check_every", m.residual_check_every, 0,
                                                        std::numeric_limits<int>::max()));
    m.static_balance_rounds = static_cast<int>(t.integer("static_balance_rounds", m.static_balance_rounds, 0,
                                                               mechanics::NscdParameters::kMaxBalanceRounds));
    // Sweep counts: integers >= 1 (checked only when mechanics is on).
    auto sweeps = [&](std::string_view key, int fallback) {
      return static_cast<int>(t.integer(key, fallback,
                                        mechanics_on ? 1 : std::numeric_limits<int>::min(),
                                        std::numeric_limits<int>::max()));
    };
    m.max_iterations = sweeps("max_iterations", m.max_iterations);
    m.retry_parts = static_cast<int>(t.integer("retry_parts", m.retry_parts, 1,
                                               mechanics::NscdParameters::kMaxRetryParts));
    m.retry_keep_steps = static_cast<int>(t.integer("retry_keep_steps", m.retry_keep_steps, 0,
                                                    std::numeric_limits<int>::max()));
    m.fallback_on_last_try = t.boolean("fallback_on_last_try", m.fallback_on_last_try);
    m.full_sweep_every = sweeps("full_sweep_every", m.full_sweep_every);
    m.tighten_steps = sweeps("tighten_steps", m.tighten_steps);
    m.settle_time_s = t.number("settle_time");
    m.coupling_interval_s = t.number("coupling_interval");
    m.settle_velocity_m_per_s = t.number("settle_velocity");
    m.compaction_speed_m_per_s = t.optional_number("compaction_speed");  // absent: automatic
    m.rest_test = t.choice("rest_test");
    m.rest_window = sweeps("rest_window", m.rest_window);
    m.rest_force_change = t.number("rest_force_change");
    m.penetration_slop = t.number("penetration_slop");
    m.recovery_speed_m_per_s = t.number("recovery_speed");
  }
  {
    const SceneTable t = section("thermal", true);
    auto& th = scene_.thermal;
    th.integrator = t.choice("integrator");
    if (const auto solver = t.choice("linear_solver"); solver != thermal::kAutoLinearSolverName)
      th.linear_solver = thermal::parse_linear_solver_kind(solver);  // the schema checked the name
    th.relative_tolerance = t.number("relative_tolerance");
    th.absolute_tolerance_K = t.number("absolute_tolerance");
    th.explicit_step_s = t.number("explicit_step");
    // The names were checked against the schema's choices, which are the kinds' names.
    th.conductance = thermal::conductance_law_from_name(t.choice("conductance"));
    const std::string law_name(thermal::name_of(th.conductance));
    if (th.conductance == thermal::ConductanceLawKind::Bahrami) check_rough_surfaces(t);
    th.constant_conductance_W_per_K = t.number("constant_conductance");
    th.contact_flattening = t.number("contact_flattening");
    if (th.contact_flattening > 0.0 && th.conductance != thermal::ConductanceLawKind::Hertz)
      t.fail("contact_flattening", "flattens the contact spot of conductance = \"hertz\", but "
                                   "conductance = \"" + law_name + "\"; set conductance = "
                                   "\"hertz\" or contact_flattening = 0");
    th.particle_resistance = thermal::parse_particle_resistance(t.choice("particle_resistance"));
    th.core_fraction = t.number("core_fraction");
    // The rays are the surrounding layer's; the Vargas-McCarthy closed form has none.
    if (th.particle_resistance == thermal::ParticleResistanceKind::IsothermalCoreRays)
      if (const auto* gas = thermal::find_heat_transfer_mode("gas_conduction");
          gas != nullptr && switched_on(scene_.effects, *gas)) {
        const std::string model(
            thermal::resolve_mode_parameters(*gas, scene_.heat_modes).choice("model"));
        if (model != "surrounding_layer")
          t.fail("particle_resistance",
                 "\"isothermal_core_rays\" integrates the shells along the surrounding layer's "
                 "rays, but fluid.model is \"" + model + "\"; set fluid.model = "
                 "\"surrounding_layer\" or particle_resistance = \"isothermal_core\"");
      }
    // The shell's resistance is a constant conductance only for constant k; with any table and
    // the Hertz law the contacts follow the Kirchhoff form (KirchhoffContactFlow.h), not handled.
    if (th.particle_resistance != thermal::ParticleResistanceKind::Off)
      for (const auto& m : scene_.materials)
        if (!m.conductivity_table.empty() ||
            (m.temperature_dependent() && th.conductance == thermal::ConductanceLawKind::Hertz))
          t.fail("particle_resistance",
                 "\"" + std::string(thermal::name_of(th.particle_resistance)) + "\" needs constant conductivities, but material \"" +
                     m.name + "\" gives its " +
                     (m.conductivity_table.empty() ? "heat capacity as a table (with conductance = "
                                                     "\"hertz\" the contacts then follow k(T))"
                                                   : "conductivity as a table") +
                     "; set particle_resistance = \"off\" or constant properties");
    th.coupling = t.choice("coupling");
    // Forces imported with the packing ([[import]] contacts) stand in for the mechanics'.
    if (contacts_carry_heat(scene_.effects) && !mechanics_on && thermal::conductance_law_uses_force(th.conductance) &&
        !scene_.imported_forces.covers_every_particle(scene_.particles.size())) {
      const std::string imported =
          scene_.imported_forces.wall_gap.empty()
              ? "import the packing with its forces ([[import]] contacts)"
              : "import every particle with its forces ([[import]] contacts; some particles "
                "have none)";
      if (t.has("conductance"))
        t.fail("conductance",
               "\"" + law_name + "\" needs contact forces but effects.mechanics = \"off\"; "
               "use conductance = \"constant\" or mechanics = \"settle\" or \"dynamic\", or " +
                   imported);
      const SceneTable effects = section("effects", true);
      effects.fail("mechanics",
                   "\"off\" leaves no contact forces for thermal.conductance = \"hertz\" "
                   "(the default); set thermal.conductance = \"constant\", or " + imported);
    }
  }
  {
    const SceneTable t = section("output", true);
    auto& o = scene_.output;
    o.file = t.optional_string("file").value_or(o.file);
    if (o.file.empty()) t.fail("file", "must not be empty");
    o.interval_s = t.number("interval");
    o.contacts = t.boolean("contacts", o.contacts);
    o.checkpoint_interval_s = t.number("checkpoint_interval");
    o.settle_checkpoint_interval_s = t.number("settle_checkpoint_interval");
  }
}

}  // namespace tmdem::coupling
