#pragma once
// The run summary of contract section 4 (written by `tmdem run --summary SUMMARY.json`).
// Key names in JSON are exactly the member names below; "message", "thermal.linear_solver" and
// "thermal.linear_solver_reason" are extra keys written only when not empty, "settle" and
// "wall_time_parts" only when set (docs/summary.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

// "mechanics.tolerance_schedule" (extra; only for scenes with mechanics.fall_tolerance): the
// tolerances, how many steps were solved at fall_tolerance (and of those unconverged: every
// step is judged against the tolerance in force at that step, so unconverged_steps counts
// both kinds), and when the tight tolerance took over.
struct ToleranceScheduleSummary {
  double tolerance = 0.0;             // mechanics.tolerance
  double fall_tolerance = 0.0;        // mechanics.fall_tolerance
  double fall_speed_m_s = 0.0;        // mechanics.fall_speed
  double fall_share = 0.0;            // mechanics.fall_share: of the particles, to begin a fall
  std::int64_t fall_steps = 0;        // steps solved at fall_tolerance
  std::int64_t fall_unconverged_steps = 0;
  std::int64_t tighten_steps = 1;     // mechanics.tighten_steps: `tolerance` from
                                      // tightened_step + tighten_steps - 1 on
  bool tightened = false;             // the fall ended at tightened_step
  std::int64_t tightened_step = 0;    // first step after the fall (1-based, of
                                      // mechanics.steps); written as null when not tightened
  double tightened_time_s = 0.0;      // s since the mechanics started (settle: of the settle
                                      // time; dynamic: of the run) when that step began; null too
};

struct MechanicsSummary {
  std::int64_t steps = 0;
  double mean_iterations = 0.0;      // Gauss-Seidel sweeps per step
  std::int64_t max_iterations = 0;
  std::int64_t unconverged_steps = 0;
  double max_penetration_m = 0.0;
  std::int64_t stalled_steps = 0;    // extra: of the unconverged steps, stopped for no progress
  std::int64_t correction_sweeps = 0;  // extra: penetration-correction sweeps over the run
  double max_step_travel_m = 0.0;    // extra: largest particle displacement in one step, m
  // extra: Siconos' residual of the steps' reactions relative to ||q|| (the measure
  // fc3d_compute_error reports), whatever the solver's own stop test: the largest, and the
  // steps where it was above the tolerance in force.
  double max_siconos_residual = 0.0;
  std::int64_t siconos_unconverged_steps = 0;
  std::optional<ToleranceScheduleSummary> tolerance_schedule{};  // extra: with a fall_tolerance
};

// The "settle" block (mechanics = "settle" only): how the packing was frozen.
struct SettleSummary {
  bool at_rest = false;              // the rest test (mechanics.rest_test) was met
  double time_s = 0.0;               // settle time used
  std::int64_t steps = 0;            // settle steps
  double max_speed_m_s = 0.0;        // largest particle speed when frozen
  // extra: which test ended the settling ("network" or "velocity"; "settle_time" when none was
  // met), and the moving particles with no contact carrying force when frozen.
  std::string ended_by;
  std::int64_t rattlers = 0;
  // extra (3D beds under gravity in plane-walled containers, coupling/run/PackingMeasure.h):
  // the bed's height along gravity (m) and the porosity of the box bounding its particles;
  // omitted (null) when not measured.
  std::optional<double> bed_height_m;
  std::optional<double> porosity;
};

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

struct EnergySummary {
  double initial_J = 0.0;
  double final_J = 0.0;
  double boundary_heat_J = 0.0;
  double balance_error_rel = 0.0;
  std::optional<MechanicalEnergySummary> mechanical;  // extra: runs with mechanics
};

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

// One entry of the "imports" list (extra): what an [[import]] of the scene brought in.
struct ImportSummary {
  std::string file;
  std::int64_t particles = 0;
  double largest_overlap_rel = 0.0;  // largest overlap among its particles / the smaller radius
  double overlap_tolerance = 0.0;    // what the scene accepted, same measure
};

// The "openmp" block (extra): the threads the run's parallel loops could use and how idle
// threads waited (OMP_WAIT_POLICY and GOMP_SPINCOUNT as the run saw them; the program bounds
// the spin when both were unset, coupling/app/OpenMpWaitPolicy.h). Figures of one run are
// comparable only at the same thread count.
struct OpenMpSummary {
  std::int64_t threads = 1;   // omp_get_max_threads() during the run
  std::string wait_policy;    // "passive", "active", or "unset" (libgomp's spin-then-sleep)
  std::string spin_count;     // GOMP_SPINCOUNT, or "unset"
};

// The "mpi" block (extra): present for a run heated over MPI (`mpirun -np N tmdem run`,
// docs/scale-out.md). Wall times in the summary are rank 0's.
struct MpiSummary {
  std::int64_t processes = 1;
  std::int64_t ghosts = 0;  // ghost copies of other processes' particles, summed over processes
};

struct RunSummary {
  std::string status = "ok";         // "ok", "failed" or "interrupted"
  std::string message;               // extra: what failed; omitted when empty
  double wall_time_s = 0.0;
  double simulated_time_s = 0.0;
  std::int64_t particles = 0;
  MechanicsSummary mechanics;
  std::optional<SettleSummary> settle;  // extra: present for settle runs only
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

}  // namespace tmdem::coupling
