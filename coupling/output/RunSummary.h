#pragma once
// The run summary of contract section 4 (written by `tmdem run --summary SUMMARY.json`).
// Key names in JSON are exactly the member names below; "message", "thermal.linear_solver" and
// "thermal.linear_solver_reason" are extra keys written only when not empty, "settle" and
// "wall_time_parts" only when set (docs/summary.md).
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

// One key of a summary block: its JSON name and the member that holds it. Each block's keys are
// listed once, after its struct (k...Fields below); RunSummary::to_json writes them and from_json
// reads them back through these lists (keys missing from a file keep the struct's default).
// omit_empty: a string written only when not empty, an optional number only when set. What a
// list does not hold (nested blocks, keys written only in some runs) is written beside it.
template <class Block, class Value>
struct SummaryField {
  const char* key;
  Value Block::*member;
  bool omit_empty = false;
};
// Deduction guides: clang 14 (Debian 12's, the sanitizer and fuzz builds) has no class template
// argument deduction for aggregates, which gcc 12 has.
template <class Block, class Value>
SummaryField(const char*, Value Block::*) -> SummaryField<Block, Value>;
template <class Block, class Value>
SummaryField(const char*, Value Block::*, bool) -> SummaryField<Block, Value>;

// "mechanics.tolerance_schedule" (extra; only for scenes with mechanics.fall_tolerance): the
// tolerances, how many steps were solved at fall_tolerance (and of those unconverged: every
// step is judged against the tolerance in force at that step, so unconverged_steps counts
// both kinds), and when the tight tolerance took over.
struct ToleranceScheduleSummary {
  double tolerance = 0.0;             // mechanics.tolerance
  double fall_tolerance = 0.0;        // mechanics.fall_tolerance
  double fall_speed_m_s = 0.0;        // mechanics.fall_speed
  double fall_share = 0.0;            // mechanics.fall_share: of the particles, to begin a fall
  double compaction_speed_m_s = 0.0;  // mechanics.compaction_speed in force at the end, the
                                      // smallest over the pistons (0: none, or off)
  std::int64_t fall_steps = 0;        // steps solved at fall_tolerance
  std::int64_t fall_unconverged_steps = 0;
  // Steps that stalled at the tight tolerance while the bed crept at a tenth of fall_speed or
  // faster, and were taken again at fall_tolerance (a collapse; ToleranceSchedule.h).
  std::int64_t collapse_steps = 0;
  std::int64_t tighten_steps = 1;     // mechanics.tighten_steps: `tolerance` from
                                      // tightened_step + tighten_steps - 1 on
  bool tightened = false;             // the fall ended at tightened_step
  std::int64_t tightened_step = 0;    // first step after the fall (1-based, of
                                      // mechanics.steps); written as null when not tightened
  double tightened_time_s = 0.0;      // s since the mechanics started (settle: of the settle
                                      // time; dynamic: of the run) when that step began; null too
};
// tightened_step and tightened_time_s are written beside the list (null until tightened).
inline constexpr std::tuple kToleranceScheduleFields{
    SummaryField{"tolerance", &ToleranceScheduleSummary::tolerance},
    SummaryField{"fall_tolerance", &ToleranceScheduleSummary::fall_tolerance},
    SummaryField{"fall_speed_m_s", &ToleranceScheduleSummary::fall_speed_m_s},
    SummaryField{"fall_share", &ToleranceScheduleSummary::fall_share},
    SummaryField{"compaction_speed_m_s", &ToleranceScheduleSummary::compaction_speed_m_s},
    SummaryField{"fall_steps", &ToleranceScheduleSummary::fall_steps},
    SummaryField{"fall_unconverged_steps", &ToleranceScheduleSummary::fall_unconverged_steps},
    SummaryField{"collapse_steps", &ToleranceScheduleSummary::collapse_steps},
    SummaryField{"tighten_steps", &ToleranceScheduleSummary::tighten_steps},
    SummaryField{"tightened", &ToleranceScheduleSummary::tightened}};

// The default solver's later stages (mechanics::FallbackCounts): written for a solver that has
// them ("nncg_ipm"), absent for the others.
struct FallbackSummary {
  std::int64_t solves = 0;
  std::int64_t converged_by_second = 0;
  std::int64_t converged_by_first_again = 0;
  std::int64_t converged_by_sweeps = 0;
  std::int64_t within_when_handed_on = 0;
  std::int64_t sweeps = 0;
  double seconds = 0.0;
  std::int64_t first_sweeps = 0;
  double first_seconds = 0.0;
};
// The wall times' keys hold "wall_time", as every wall time of the summary: comparisons of runs
// bit for bit leave them out (tests/e2e/ResultComparison.h).
inline constexpr std::tuple kFallbackSummaryFields{
    SummaryField{"solves", &FallbackSummary::solves},
    SummaryField{"converged_by_second", &FallbackSummary::converged_by_second},
    SummaryField{"converged_by_first_again", &FallbackSummary::converged_by_first_again},
    SummaryField{"converged_by_sweeps", &FallbackSummary::converged_by_sweeps},
    SummaryField{"within_when_handed_on", &FallbackSummary::within_when_handed_on},
    SummaryField{"sweeps", &FallbackSummary::sweeps},
    SummaryField{"wall_time_s", &FallbackSummary::seconds},
    SummaryField{"first_sweeps", &FallbackSummary::first_sweeps},
    SummaryField{"first_wall_time_s", &FallbackSummary::first_seconds}};

struct MechanicsSummary {
  std::int64_t steps = 0;
  double mean_iterations = 0.0;      // Gauss-Seidel sweeps per step
  std::int64_t max_iterations = 0;
  std::int64_t unconverged_steps = 0;
  double max_penetration_m = 0.0;
  std::int64_t stalled_steps = 0;    // extra: of the unconverged steps, stopped for no progress
  std::int64_t correction_sweeps = 0;  // extra: penetration-correction sweeps over the run
  // extra: steps taken as two halves (or more) because particles could move apart across the
  // periods by more than they allow (mechanics::NscdIntegrator::step); each half is in `steps`
  std::int64_t halved_steps = 0;
  // extra: steps taken in equal parts because a moving wall landed faster than a radius a step
  std::int64_t landing_halved_steps = 0;
  // extra: steps retaken in parts after ending unconverged (mechanics.retry_parts), and the
  // sweeps of the tries thrown away (not in mean_iterations)
  std::int64_t retried_steps = 0;
  std::int64_t discarded_sweeps = 0;
  // extra: steps started in the parts an earlier retry needed (mechanics.retry_keep_steps)
  std::int64_t kept_parts_steps = 0;
  // extra: steps listed with a piston's likely reach whose travel left the table: listed again
  // with the bound and solved again (mechanics estimate_wall_reach)
  std::int64_t relisted_steps = 0;
  // extra: corrections in which pistons took their share (particles pinned under a piston)
  std::int64_t piston_corrections = 0;
  double max_step_travel_m = 0.0;    // extra: largest particle displacement in one step, m
  // extra: Siconos' residual of the steps' reactions relative to ||q|| (the measure
  // fc3d_compute_error reports), whatever the solver's own stop test: the largest, and the
  // steps where it was above the tolerance in force.
  double max_siconos_residual = 0.0;
  std::int64_t siconos_unconverged_steps = 0;
  // extra: the largest natural-map residual of the steps' reactions in the bodies' metric
  // (each reaction against its own exact local solution, relative to the reactions): what the
  // figure above does not see on light bodies (docs/mechanics.md "Honest convergence").
  double max_natural_map_residual = 0.0;
  // extra: steps of mechanics.time_step that ended unconverged, a step taken in parts counted
  // once (unconverged_steps counts each unconverged part); one warning each, the first 10 shown
  std::int64_t unconverged_time_steps = 0;
  std::optional<ToleranceScheduleSummary> tolerance_schedule{};  // extra: with a fall_tolerance
  std::optional<FallbackSummary> fallback{};  // extra: with a solver that has later stages
};
inline constexpr std::tuple kMechanicsSummaryFields{
    SummaryField{"steps", &MechanicsSummary::steps},
    SummaryField{"mean_iterations", &MechanicsSummary::mean_iterations},
    SummaryField{"max_iterations", &MechanicsSummary::max_iterations},
    SummaryField{"unconverged_steps", &MechanicsSummary::unconverged_steps},
    SummaryField{"max_penetration_m", &MechanicsSummary::max_penetration_m},
    SummaryField{"stalled_steps", &MechanicsSummary::stalled_steps},
    SummaryField{"correction_sweeps", &MechanicsSummary::correction_sweeps},
    SummaryField{"halved_steps", &MechanicsSummary::halved_steps},
    SummaryField{"landing_halved_steps", &MechanicsSummary::landing_halved_steps},
    SummaryField{"retried_steps", &MechanicsSummary::retried_steps},
    SummaryField{"discarded_sweeps", &MechanicsSummary::discarded_sweeps},
    SummaryField{"kept_parts_steps", &MechanicsSummary::kept_parts_steps},
    SummaryField{"relisted_steps", &MechanicsSummary::relisted_steps},
    SummaryField{"piston_corrections", &MechanicsSummary::piston_corrections},
    SummaryField{"max_step_travel_m", &MechanicsSummary::max_step_travel_m},
    SummaryField{"max_siconos_residual", &MechanicsSummary::max_siconos_residual},
    SummaryField{"siconos_unconverged_steps", &MechanicsSummary::siconos_unconverged_steps},
    SummaryField{"max_natural_map_residual", &MechanicsSummary::max_natural_map_residual},
    SummaryField{"unconverged_time_steps", &MechanicsSummary::unconverged_time_steps}};

// The "settle" block of a run with a settle phase (mechanics "settle" and "coupled"): how the
// packing was frozen (RunSummary::settle for the others).
struct SettleSummary {
  bool at_rest = false;              // the rest test (mechanics.rest_test) was met
  double time_s = 0.0;               // settle time used
  std::int64_t steps = 0;            // settle steps
  double max_speed_m_s = 0.0;        // largest particle speed when frozen
  // extra: which test ended the settling ("network" or "velocity"; "settle_time" when none was
  // met; "interrupted" when a signal stopped it first), and the moving particles with no
  // contact carrying force when frozen.
  std::string ended_by;
  std::int64_t rattlers = 0;
  // extra (3D beds under gravity in plane-walled containers, coupling/run/PackingMeasure.h):
  // the bed's height along gravity (m) and the porosity of the box bounding its particles;
  // omitted (null) when not measured.
  std::optional<double> bed_height_m;
  std::optional<double> porosity;
};
// The "settle" block's ended_by for a run without a settle phase (RunSummary::settle).
inline constexpr const char* kNoSettlePhase = "none";
inline constexpr std::tuple kSettleSummaryFields{
    SummaryField{"at_rest", &SettleSummary::at_rest},
    SummaryField{"time_s", &SettleSummary::time_s},
    SummaryField{"steps", &SettleSummary::steps},
    SummaryField{"max_speed_m_s", &SettleSummary::max_speed_m_s},
    SummaryField{"ended_by", &SettleSummary::ended_by},
    SummaryField{"rattlers", &SettleSummary::rattlers},
    SummaryField{"bed_height_m", &SettleSummary::bed_height_m, true},
    SummaryField{"porosity", &SettleSummary::porosity, true}};

// The "thermo_mechanics" block (extra; effects.mechanics = "coupled" only): the quasi-static
// re-solves of the packing during the heating, and the walls' forces (N, the sum of the normal
// forces of each wall's contacts, one entry per [[wall]] in scene order) and points (m).
struct ThermoMechanicsSummary {
  std::int64_t couplings = 0;           // re-solves of the packing after t = 0
  std::int64_t steps = 0;               // mechanical steps over them
  std::int64_t not_at_rest = 0;         // re-solves that ran out of mechanics.settle_time
  std::vector<double> largest_wall_force_N;  // over the run's frames
  std::vector<double> last_wall_force_N;
  std::vector<double> last_wall_point_m;     // 3 per wall
};
inline constexpr std::tuple kThermoMechanicsSummaryFields{
    SummaryField{"couplings", &ThermoMechanicsSummary::couplings},
    SummaryField{"steps", &ThermoMechanicsSummary::steps},
    SummaryField{"not_at_rest", &ThermoMechanicsSummary::not_at_rest},
    SummaryField{"largest_wall_force_N", &ThermoMechanicsSummary::largest_wall_force_N},
    SummaryField{"last_wall_force_N", &ThermoMechanicsSummary::last_wall_force_N},
    SummaryField{"last_wall_point_m", &ThermoMechanicsSummary::last_wall_point_m}};

struct ThermalSummary {
  std::string integrator = "cvode";  // "cvode", "ida" or "explicit"
  std::string linear_solver;         // extra: "klu", "pcg" or "amg" (as resolved from "auto");
                                     // omitted when empty (explicit update, failed before)
  std::string linear_solver_reason;  // extra: why that one, e.g. "auto: 25000 particles >= 5000
                                     // in 3D, symmetric Jacobian"; omitted when empty
  std::int64_t steps = 0;
  std::int64_t rhs_evals = 0;
  std::int64_t jacobian_evals = 0;
  std::int64_t linear_setups = 0;
  std::int64_t error_test_failures = 0;
  std::int64_t convergence_failures = 0;
  std::int64_t reinitializations = 0;
  double wall_time_s = 0.0;          // extra: time spent in the thermal side alone
  std::string coupling;              // extra: thermal.coupling of a dynamic run ("restart" for a
                                     // coupled run, which re-initialises at every coupling);
                                     // omitted when empty
};
inline constexpr std::tuple kThermalSummaryFields{
    SummaryField{"integrator", &ThermalSummary::integrator},
    SummaryField{"linear_solver", &ThermalSummary::linear_solver, true},
    SummaryField{"linear_solver_reason", &ThermalSummary::linear_solver_reason, true},
    SummaryField{"steps", &ThermalSummary::steps},
    SummaryField{"rhs_evals", &ThermalSummary::rhs_evals},
    SummaryField{"jacobian_evals", &ThermalSummary::jacobian_evals},
    SummaryField{"linear_setups", &ThermalSummary::linear_setups},
    SummaryField{"error_test_failures", &ThermalSummary::error_test_failures},
    SummaryField{"convergence_failures", &ThermalSummary::convergence_failures},
    SummaryField{"reinitializations", &ThermalSummary::reinitializations},
    SummaryField{"wall_time_s", &ThermalSummary::wall_time_s},
    SummaryField{"coupling", &ThermalSummary::coupling, true}};

// extra: energy.mechanical, runs with mechanics (settle: the settle phase). The mechanics' energy account over the run
// (mechanics/integrator/NscdIntegrator.h): energy_change + contact_dissipation + numerical_dissipation = 0
// exactly in arithmetic; balance_error_rel measures it. With a mode that turns the contacts'
// dissipation into heat (effects.friction_heat), heat_generated_J is what the run handed to the
// thermal side (each step's contact powers times the time it advanced), heat_received_J what the
// integrator really integrated of the free particles' share of it (its own quadrature), and
// heat_error_rel the worse of |heat_generated - contact_dissipation| / |contact_dissipation| and
// |heat_received - heat_share| / max(|heat_share|, |heat_received|), heat_share the exact
// integral of that piecewise-constant share (0 when both are 0); these keys are written only then.
struct MechanicalEnergySummary {
  double energy_change_J = 0.0;          // kinetic + gravitational potential, end - start
  double contact_dissipation_J = 0.0;    // sum over steps and contacts of -r . u_theta
  double numerical_dissipation_J = 0.0;  // theta scheme's damping, (theta - 1/2) |dv|_M^2
  double balance_error_rel = 0.0;        // |change + contact + numerical| / max(|change|, |contact| + |numerical|)
  // Potential-energy change made by the penetration correction's position-only moves, J
  // (> 0: particles lifted); outside the balance above, which covers the velocity steps.
  double correction_potential_J = 0.0;
  bool heat = false;                     // heat_generated_J and heat_error_rel are meaningful
  double heat_generated_J = 0.0;
  double heat_received_J = 0.0;          // integrated by the thermal integrator (free particles)
  double heat_share_J = 0.0;             // exact: sum over steps of the particles' share x step (not written)
  double heat_error_rel = 0.0;           // see above

  // This account with balance_error_rel (and, when `heat_on`, heat_error_rel) filled in.
  MechanicalEnergySummary with_errors(bool heat_on) const;
};
inline constexpr std::tuple kMechanicalEnergyFields{
    SummaryField{"energy_change_J", &MechanicalEnergySummary::energy_change_J},
    SummaryField{"contact_dissipation_J", &MechanicalEnergySummary::contact_dissipation_J},
    SummaryField{"numerical_dissipation_J", &MechanicalEnergySummary::numerical_dissipation_J},
    SummaryField{"balance_error_rel", &MechanicalEnergySummary::balance_error_rel},
    SummaryField{"correction_potential_J", &MechanicalEnergySummary::correction_potential_J}};
// Written only with `heat` (which a file tells by heat_generated_J); heat_share_J never.
inline constexpr std::tuple kMechanicalHeatFields{
    SummaryField{"heat_generated_J", &MechanicalEnergySummary::heat_generated_J},
    SummaryField{"heat_received_J", &MechanicalEnergySummary::heat_received_J},
    SummaryField{"heat_error_rel", &MechanicalEnergySummary::heat_error_rel}};

struct EnergySummary {
  double initial_J = 0.0;
  double final_J = 0.0;
  double boundary_heat_J = 0.0;
  double balance_error_rel = 0.0;
  std::optional<MechanicalEnergySummary> mechanical;  // extra: runs with mechanics
};
inline constexpr std::tuple kEnergySummaryFields{
    SummaryField{"initial_J", &EnergySummary::initial_J},
    SummaryField{"final_J", &EnergySummary::final_J},
    SummaryField{"boundary_heat_J", &EnergySummary::boundary_heat_J},
    SummaryField{"balance_error_rel", &EnergySummary::balance_error_rel}};

// The "wall_time_parts" block (extra): where the run's wall time went, s, measured around the
// calls of the coupled run loop. The first four add up to wall_time_s; the last three are parts
// of mechanics_s, timed inside each NSCD step (mechanics::StepReport), 0 in summaries written
// before they existed.
struct WallTimeParts {
  double mechanics_s = 0.0;  // NSCD steps, settle and dynamic: contact detection + contact solve
  double thermal_s = 0.0;    // the thermal side (= thermal.wall_time_s)
  double output_s = 0.0;     // frames (HDF5 + XDMF) and checkpoints
  double other_s = 0.0;      // the rest: set-up, scene checks, summary
  double detection_s = 0.0;      // of mechanics_s: candidate refresh, gaps, normals, warm start
  double contact_solve_s = 0.0;  // of mechanics_s: the velocity-level contact solve
  double correction_s = 0.0;     // of mechanics_s: penetration correction (position-only)
};
inline constexpr std::tuple kWallTimePartsFields{
    SummaryField{"mechanics_s", &WallTimeParts::mechanics_s},
    SummaryField{"thermal_s", &WallTimeParts::thermal_s},
    SummaryField{"output_s", &WallTimeParts::output_s},
    SummaryField{"other_s", &WallTimeParts::other_s},
    SummaryField{"detection_s", &WallTimeParts::detection_s},
    SummaryField{"contact_solve_s", &WallTimeParts::contact_solve_s},
    SummaryField{"correction_s", &WallTimeParts::correction_s}};

// One entry of the "imports" list (extra): what an [[import]] of the scene brought in.
struct ImportSummary {
  std::string file;
  std::int64_t particles = 0;
  double largest_overlap_rel = 0.0;  // largest overlap among its particles / the smaller radius
  double overlap_tolerance = 0.0;    // what the scene accepted, same measure
};
inline constexpr std::tuple kImportSummaryFields{
    SummaryField{"file", &ImportSummary::file},
    SummaryField{"particles", &ImportSummary::particles},
    SummaryField{"largest_overlap_rel", &ImportSummary::largest_overlap_rel},
    SummaryField{"overlap_tolerance", &ImportSummary::overlap_tolerance}};

// The "openmp" block (extra): the threads the run's parallel loops could use and how idle
// threads waited (OMP_WAIT_POLICY and GOMP_SPINCOUNT as the run saw them; the program bounds
// the spin when both were unset, coupling/app/OpenMpWaitPolicy.h). Figures of one run are
// comparable only at the same thread count.
struct OpenMpSummary {
  std::int64_t threads = 1;   // omp_get_max_threads() during the run
  std::string wait_policy;    // "passive", "active", or "unset" (libgomp's spin-then-sleep)
  std::string spin_count;     // GOMP_SPINCOUNT, or "unset"
};
inline constexpr std::tuple kOpenMpSummaryFields{
    SummaryField{"threads", &OpenMpSummary::threads},
    SummaryField{"wait_policy", &OpenMpSummary::wait_policy},
    SummaryField{"spin_count", &OpenMpSummary::spin_count}};

// The "mpi" block (extra): present for a run heated over MPI (`mpirun -np N tmdem run`,
// docs/scale-out.md). Wall times in the summary are rank 0's.
struct MpiSummary {
  std::int64_t processes = 1;
  std::int64_t ghosts = 0;  // ghost copies of other processes' particles, summed over processes
};
inline constexpr std::tuple kMpiSummaryFields{SummaryField{"processes", &MpiSummary::processes},
                                               SummaryField{"ghosts", &MpiSummary::ghosts}};

struct RunSummary {
  std::string status = "ok";         // "ok", "failed" or "interrupted"
  std::string message;               // extra: what failed; omitted when empty
  double wall_time_s = 0.0;
  double simulated_time_s = 0.0;
  std::int64_t particles = 0;
  MechanicsSummary mechanics;
  // Settle and coupled runs: their settle phase. A run without one still gets the contract's
  // "settle" block (to_json): at rest with no settle time, no steps and speed 0 when the packing
  // is held as given (packing_held: mechanics "off"), else at_rest and max_speed_m_s null (a
  // dynamic run moves its packing for the whole run; a run that stopped before settling never
  // judged it); its ended_by is "none".
  std::optional<SettleSummary> settle;
  bool packing_held = false;
  std::optional<ThermoMechanicsSummary> thermo_mechanics;  // extra: "coupled" runs only
  ThermalSummary thermal;
  EnergySummary energy;
  std::optional<WallTimeParts> wall_time_parts;  // extra: present for runs that got going
  std::vector<ImportSummary> imports;            // extra: written only when not empty
  std::optional<OpenMpSummary> openmp;           // extra: present for runs that got going
  std::optional<MpiSummary> mpi;                 // extra: runs heated over MPI only

  nlohmann::json to_json() const;
  // Inverse of to_json (missing keys keep their defaults). Throws nlohmann::json::exception on
  // wrong types.
  static RunSummary from_json(const nlohmann::json& j);
  // Pretty-printed JSON plus newline. Throws OutputError naming the path.
  void write(const std::string& path) const;

  // |final - initial - boundary_heat| / max(|initial|, |boundary_heat|); 0 when both are 0.
  static double balance_error_rel(double initial_J, double final_J, double boundary_heat_J);
};
// The top level's own keys (the blocks above are written beside them).
inline constexpr std::tuple kRunSummaryFields{
    SummaryField{"status", &RunSummary::status},
    SummaryField{"message", &RunSummary::message, true},
    SummaryField{"wall_time_s", &RunSummary::wall_time_s},
    SummaryField{"simulated_time_s", &RunSummary::simulated_time_s},
    SummaryField{"particles", &RunSummary::particles}};

}  // namespace tmdem::coupling
