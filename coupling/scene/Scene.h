#pragma once
// The resolved scene: everything from the TOML file after generation and [[assign]], validated.
// Field names follow contract section 2; units are SI and stated per field.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mechanics/integrator/NscdParameters.h"
#include "mechanics/model/PeriodicBox.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "coupling/scene/Probe.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ParticleResistanceKind.h"
#include "thermal/modes/ModeSettings.h"

namespace tmdem::coupling {

using Vec3 = std::array<double, 3>;

// Coupled: settle as Settle, then during the heating the packing is solved again
// quasi-statically every mechanics.coupling_interval with the radii of the current
// temperatures (thermal expansion), and the network follows (coupling/run/ThermalExpansion.h).
enum class MechanicsMode { Off, Settle, Dynamic, Coupled };

// The defaults of a [[material]]'s optional keys are written here once: the scene schema
// (SceneSchema.cpp, so docs/scene.md and the loader) takes them from a default Material, and
// tests/coupling/scene/test_scene_defaults.cpp holds the two together.
struct Material {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double young_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  double friction = 0.3;                 // Coulomb coefficient
  double rolling_friction = 0.0;         // rolling resistance mu_r (torque <= mu_r R_eff N)
  double conductivity_W_per_mK = 0.0;    // with a table: its first value (the reference)
  double heat_capacity_J_per_kgK = 0.0;  // specific heat c; with a table: its first value
  double emissivity = 0.0;               // 0..1
  // Linear thermal expansion coefficient alpha, 1/K: a particle's radius is r0 (1 + alpha (T - T0))
  // with r0 and T0 its radius and temperature at the start (effects.mechanics = "coupled").
  double thermal_expansion_per_K = 0.0;
  // Surface, for thermal.conductance = "bahrami" (thermal/modes/RoughContactConductance.h): RMS
  // roughness sigma (m; 0: smooth), mean absolute asperity slope, microhardness (Pa; 0: not given).
  double roughness_m = 0.0;
  double asperity_slope = 0.0;
  double microhardness_Pa = 0.0;
  // [T_K, value] points when the scene gives the property as a table (piecewise linear in T,
  // clamped outside); empty for a constant.
  std::vector<std::array<double, 2>> conductivity_table;
  std::vector<std::array<double, 2>> heat_capacity_table;
  bool temperature_dependent() const {
    return !conductivity_table.empty() || !heat_capacity_table.empty();
  }
};

struct Particle {
  Vec3 position_m{};
  double radius_m = 0.0;
  int material = 0;                 // index into Scene::materials
  double temperature_K = 293.15;
  bool fixed_temperature = false;   // held at temperature_K for the whole run
  double heat_source_W = 0.0;
  bool fixed = false;               // does not move
};

struct Wall {
  Vec3 point_m{};                   // plane: a point of it; cylinder: a point of the axis
  Vec3 normal{};                    // unit; plane: points into the domain; cylinder: the axis
  int material = 0;
  bool cylinder = false;            // shape = "cylinder": particles inside, radius_m from the axis
  double radius_m = 0.0;
  std::optional<double> temperature_K;  // set: isothermal; unset: adiabatic (a table: its value at t = 0)
  // temperature = [[t_s, T_K], ...]: piecewise linear in time, clamped; empty: constant.
  std::vector<std::array<double, 2>> temperature_table;
  // Imposed heat flux into the bed, W/m^2 (negative: heat taken out), over heat_flux_area_m2;
  // the power is shared among the touching particles by conductance. Excludes temperature.
  std::optional<double> heat_flux_W_per_m2;
  double heat_flux_area_m2 = 0.0;
  // piston = true (planes): the wall moves along its normal, pushed into the domain by
  // piston_force_N plus its weight (mechanics/model/Wall.h). The force is `force`, or `pressure` x
  // `pressure_area` (then both are kept, so a study can impose other pressures).
  bool piston = false;
  double piston_mass_kg = 0.0;
  double piston_force_N = 0.0;
  std::optional<double> piston_pressure_Pa;
  double piston_area_m2 = 0.0;  // pressure_area; 0: not given
  // start = "on_bed": the loader moved point_m along the normal onto the particles' top (the
  // plane touches the particle that reaches farthest against the normal); false: as given.
  bool piston_start_on_bed = false;
};

// Signed distance of x from the wall's surface, m (positive inside the domain).
inline double wall_signed_distance(const Wall& w, const Vec3& x) {
  double along = 0.0, d2 = 0.0;
  for (int k = 0; k < 3; ++k) along += (x[k] - w.point_m[k]) * w.normal[k];
  if (!w.cylinder) return along;
  for (int k = 0; k < 3; ++k) {
    const double r = x[k] - w.point_m[k] - along * w.normal[k];
    d2 += r * r;
  }
  return w.radius_m - std::sqrt(d2);
}

// What one [[import]] brought in; printed by `tmdem run` (stderr) and `tmdem check`
// (describe_import, coupling/scene/ParticleImport.h).
struct ImportReport {
  std::string origin;       // "import[0]"
  std::string file;
  std::string format;       // the format read (coupling/scene/PackingFormats.h)
  std::string description;  // e.g. "frame 20 of 21 (t = 1 s)"; may be empty
  std::size_t first_id = 0;
  std::size_t count = 0;
  std::vector<std::string> ignored_columns;
  double overlap_tolerance = 1e-9;  // fraction of the smaller radius accepted among its particles
  // overlaps = "hold": the overlaps found are the packing's, held by the position step
  // (NscdIntegrator::hold_initial_overlaps); "push_out": the position step removes them.
  bool hold_overlaps = true;
  // Largest overlap among its particles (and between them and the walls), as a fraction of the
  // smaller radius, and in m; 0 when none overlap. largest_overlap_between: "particles 3 and 17".
  double largest_overlap = 0.0;
  double largest_overlap_m = 0.0;
  std::string largest_overlap_between;
  // contacts = "...": the local dump its pair forces came from, how many, of which timestep.
  std::string contacts_file;
  std::size_t contact_count = 0;
  long long contacts_timestep = 0;
};

// A pair contact with its normal force, from an [[import]] with contacts (a LAMMPS / LIGGGHTS
// local dump): scene particle ids i < j, forces in N. force_on_i_N: the whole contact force on
// i when the file gives the vector (tangential part included), else the normal force along
// (x_i - x_j)/|x_i - x_j|; the wall forces balance it (coupling/bridge/RestingContacts.h).
struct ImportedContact {
  std::size_t i = 0, j = 0;
  double normal_force_N = 0.0;
  Vec3 force_on_i_N{};
};

// The contacts and forces [[import]] read with its particles; effects.mechanics = "off" uses
// them instead of touching pairs of zero force (coupling/bridge/RestingContacts.h).
struct ImportedForces {
  std::vector<ImportedContact> pairs;  // sorted by (i, j)
  // Per scene particle: the gap to a wall, as a fraction of its radius, up to which it rests on
  // the wall (its wall force then comes from its balance); < 0: its forces are not imported.
  // Empty when no [[import]] has contacts.
  std::vector<double> wall_gap;
  bool imported(std::size_t particle) const {
    return particle < wall_gap.size() && wall_gap[particle] >= 0.0;
  }
  bool covers_every_particle(std::size_t count) const {
    for (std::size_t p = 0; p < count; ++p)
      if (!imported(p)) return false;
    return count > 0;
  }
};

struct Effects {
  MechanicsMode mechanics = MechanicsMode::Settle;
  // effects.<key> of the heat-transfer modes ("conduction", "convection", ...), every key the
  // registered modes declare (thermal/modes/ModeDescription.h), defaults filled in by the loader.
  std::map<std::string, bool, std::less<>> heat;
  bool on(std::string_view key) const {
    const auto it = heat.find(key);
    return it != heat.end() && it->second;
  }
};

// The defaults of [mechanics], [thermal] and [output] are written here once: the scene schema
// (SceneSchemaSettings.cpp, so docs/scene.md) takes them from these structs, and
// tests/coupling/scene/test_scene_defaults.cpp loads every key at the default the reference
// states and compares with these. The mechanics defaults are the mechanics library's
// (mechanics::NscdParameters).
struct MechanicsSettings {
  double time_step_s = mechanics::NscdParameters{}.time_step;
  double theta = mechanics::NscdParameters{}.theta;
  std::string solver = mechanics::NscdParameters{}.solver;  // mechanics::contact_solver_names()
  double tolerance = mechanics::NscdParameters{}.tolerance;
  // Tolerance schedule (mechanics::ToleranceSchedule): fall_tolerance from the first step at
  // which fall_share of the particles move at or above fall_speed, until the fastest is below;
  // fall_tolerance 0 = off; fall_speed 0 = automatic (a tenth of the smallest radius per step).
  double fall_tolerance = mechanics::NscdParameters{}.fall_tolerance;
  double fall_speed_m_per_s = mechanics::NscdParameters{}.fall_speed;
  double fall_share = mechanics::NscdParameters{}.fall_share;  // of the moving particles
  // A piston at or above this speed keeps the schedule falling (its load compacts the bed);
  // absent: automatic (mechanics::NscdParameters::compaction_speed); 0 = off.
  std::optional<double> compaction_speed_m_per_s = mechanics::NscdParameters{}.compaction_speed;
  double stop_travel = mechanics::NscdParameters{}.stop_travel_fraction;  // of r_min per step
  bool skip_out_of_reach = mechanics::NscdParameters{}.skip_out_of_reach;
  bool estimate_piston_reach = mechanics::NscdParameters{}.estimate_wall_reach;
  bool static_warm_start = mechanics::NscdParameters{}.static_warm_start;
  // Sweeps between checks of Siconos' residual before nncg's sweep test is met (0: never).
  int residual_check_every = mechanics::NscdParameters{}.residual_check_every;
  int static_balance_rounds = mechanics::NscdParameters{}.static_balance_rounds;
  int tighten_steps = mechanics::NscdParameters{}.tighten_steps;  // fall_tolerance -> tolerance over this many steps
  int max_iterations = mechanics::NscdParameters{}.max_iterations;
  // An unconverged step is retaken in 2, 4, ... parts up to this (NscdParameters::retry_parts).
  int retry_parts = mechanics::NscdParameters{}.retry_parts;
  // Converged steps that halve the parts kept after a retry (NscdParameters::retry_keep_steps).
  int retry_keep_steps = mechanics::NscdParameters{}.retry_keep_steps;
  // The solver's later stages only on a step's last try (NscdParameters::fallback_on_last_try).
  bool fallback_on_last_try = mechanics::NscdParameters{}.fallback_on_last_try;
  int full_sweep_every = mechanics::NscdParameters{}.full_sweep_every;  // Gauss-Seidel active-set sweeps
  // "sweep" or "siconos" (mechanics::NscdParameters::siconos_stop)
  std::string stop_test = mechanics::NscdParameters{}.siconos_stop ? "siconos" : "sweep";
  mechanics::NormalLaw normal_law = mechanics::NscdParameters{}.normal_law;  // "rigid" or "hertz"
  double coupling_interval_s = 60.0;  // "coupled": heating time between two re-solves of the packing
  double settle_time_s = 5.0;         // the longest settle phase
  double settle_velocity_m_per_s = 1.0e-4;
  // When "settle" ends (coupling/run/SettleRestTest.h): "network" when the normal forces have
  // stopped changing and the load carriers have stopped, "velocity" when every particle is
  // slower than settle_velocity.
  std::string rest_test = "network";
  int rest_window = 5;              // steps
  double rest_force_change = 1e-2;  // relative
  double penetration_slop = mechanics::NscdParameters{}.penetration_slop_fraction;  // of the smallest radius
  double recovery_speed_m_per_s = mechanics::NscdParameters{}.recovery_speed;  // 0 = no cap

  friend bool operator==(const MechanicsSettings&, const MechanicsSettings&) = default;
};

struct ThermalSettings {
  std::string integrator{thermal::name_of(thermal::kDefaultIntegrator)};  // thermal_integrator_names()
  // thermal.linear_solver, parsed once here; empty: "auto", turned into a solver by each run
  // from its problem (coupling/run/LinearSolverChoice.h).
  std::optional<thermal::LinearSolverKind> linear_solver;
  double relative_tolerance = 1.0e-6;
  double absolute_tolerance_K = 1.0e-6;
  double explicit_step_s = 0.0;        // 0 = 0.9 x the stability bound
  thermal::ConductanceLawKind conductance = thermal::ConductanceLawKind::Hertz;
  double constant_conductance_W_per_K = 1.0e-4;
  // Hertz law: a loaded contact's spot radius is at least contact_flattening x R* (0: Hertz).
  double contact_flattening = 0.0;
  // The particle's own resistance in series with its contact and gas paths
  // (thermal/modes/ParticleResistance.h); core radius c r.
  thermal::ParticleResistanceKind particle_resistance = thermal::ParticleResistanceKind::Off;
  double core_fraction = 0.5;
  // Dynamic runs (extension): how the implicit integrators follow the moving packing.
  // "continue": keep the step history while contacts only change force, re-initialise when
  //             contacts appear or vanish; "restart": re-initialise every mechanical step.
  std::string coupling = "continue";

  friend bool operator==(const ThermalSettings&, const ThermalSettings&) = default;
};

struct OutputSettings {
  std::string file = "result.h5";
  double interval_s = 0.1;
  bool contacts = true;
  double checkpoint_interval_s = 0.0;
  // Wall-clock seconds between settle checkpoints (a long settle survives a crash); 0: none.
  double settle_checkpoint_interval_s = 600.0;

  friend bool operator==(const OutputSettings&, const OutputSettings&) = default;
};

// [periodic]: the axes along which space repeats, each with its period [low, high) (m). The
// particles are wrapped into it at load; walls must be planes parallel to every periodic axis.
struct PeriodicSettings {
  std::array<bool, 3> axis{false, false, false};
  Vec3 low_m{}, high_m{};
  bool any() const { return axis[0] || axis[1] || axis[2]; }
  double length_m(int a) const { return high_m[std::size_t(a)] - low_m[std::size_t(a)]; }
};

// The mechanics' view of [periodic] (no axis: a box that changes nothing).
inline mechanics::PeriodicBox periodic_box(const PeriodicSettings& p) {
  mechanics::PeriodicBox box;
  box.periodic = p.axis;
  for (int a = 0; a < 3; ++a) {
    box.low[a] = p.low_m[std::size_t(a)];
    box.high[a] = p.high_m[std::size_t(a)];
  }
  return box;
}

struct Scene {
  double duration_s = 0.0;
  int dimension = 3;
  Vec3 gravity_m_per_s2{0.0, 0.0, 0.0};
  std::uint64_t seed = 1;
  Effects effects;
  std::vector<Material> materials;
  // ids: explicit [[particle]] first, then each [[generate]], then each [[import]]
  std::vector<Particle> particles;
  std::vector<Wall> walls;
  PeriodicSettings periodic;          // none by default
  std::vector<ImportReport> imports;  // one per [[import]], in file order
  ImportedForces imported_forces;     // from [[import]] contacts; empty without
  // Every registered mode's parameters from its own section (defaults filled in), by mode name
  // and key: heat_modes.find("convection", "coefficient").
  thermal::ModeSettings heat_modes;
  MechanicsSettings mechanics;
  ThermalSettings thermal;
  OutputSettings output;
  std::vector<Probe> probes;        // [[probe]], in file order (coupling/scene/SceneProbes.h)
  // What loading found legal but likely unmeant (a deposit laid above its floor:
  // DepositSupport.h), one sentence each without a "warning: " prefix; tmdem check and tmdem
  // run print them.
  std::vector<std::string> warnings;
  std::string resolved_toml;        // the scene as TOML text after --set overrides
  std::string source;               // file path, or "<default scene>"
};

}  // namespace tmdem::coupling
