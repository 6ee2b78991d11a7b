#pragma once
// `tmdem study conductivity`: the effective conductivity of a bed from one steady state.
//
// The scene names the measurement by its walls: exactly two walls have a `temperature`, they
// face each other (opposite normals) and their temperatures differ; every other wall is
// adiabatic. The packing is taken as the scene gives it (mechanics "off": contacts from
// geometry), or settled first ("settle"; a "dynamic" scene is settled the same way). Then the
// steady state q(T) = 0 is solved directly (thermal/steady/SteadyStateSolver.h: Newton + KLU on the
// conductance Laplacian with the scene's modes, no time stepping) and
//   k_eff = Q L / (A dT)
// with Q the heat through the hot wall, W; L the distance between the two wall planes, m;
// A the cross-section normal to the axis, m^2: in each of the two directions across the axis,
// the period if the scene is periodic along it ([periodic]: a bulk bed between the two walls,
// no side walls), else the gap between opposite side walls if the scene has them, else the
// particles' extent
// (max of x + r minus min of x - r; in 2D the z extent is one diameter); dT = T_hot - T_cold.
// Porosity = 1 - (sum of sphere volumes 4/3 pi r^3) / (A L). Coordination number = 2 x the
// particle-particle contacts / particles (settled packings: contacts with a positive normal
// force; mechanics "off": every touching pair).
//
// Share of each mode: with x_i the distance of particle i from the hot wall, a mode m that
// moves heat between bodies carries T_m = sum_i q_i^m x_i + L Q_cold^m (W m), q_i^m its heat
// flow into particle i and Q_cold^m the heat it delivers to the cold wall. At the steady state
// the T_m add up to L Q_cold exactly (every free particle's flows cancel), so
// share_m = T_m / (L Q_cold) sums to 1 to round-off: it is the part of the heat transport
// across the bed that mode m carries. A mode's wall heat is measured by evaluating it on the
// network with the other wall's edges removed (modes exchange with walls only through wall
// edges), so new modes (gas, radiation) need nothing here.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "coupling/output/ProgressReporter.h"
#include "coupling/run/MechanicsStepLog.h"
#include "coupling/scene/Scene.h"
#include "thermal/integrators/IntegratorKind.h"

namespace tmdem::coupling {

struct ModeShare {
  std::string mode;          // registered mode name
  double hot_wall_W = 0.0;   // heat this mode takes from the hot wall into the particles
  double cold_wall_W = 0.0;  // heat this mode delivers to the cold wall
  double share = 0.0;        // of the transport across the bed (see above)
};

struct ConductivityResult {
  std::optional<double> pressure_Pa;   // the piston's pressure (--pressures, or its pressure key)
  std::size_t hot_wall = 0, cold_wall = 0;  // indices into scene.walls
  double T_hot_K = 0.0, T_cold_K = 0.0;
  double length_m = 0.0, area_m2 = 0.0;
  std::string periodic_axes;   // "x, z": the periods give A (and the porosity's volume A L)
  double heat_hot_W = 0.0;     // into the bed through the hot wall
  double heat_cold_W = 0.0;    // out of the bed through the cold wall
  double balance_rel = 0.0;    // |heat_hot - heat_cold| / |heat_hot|
  double k_eff_W_per_mK = 0.0;
  double porosity = 0.0;
  double coordination = 0.0;
  std::size_t particles = 0, contacts = 0, wall_contacts = 0;
  std::size_t hot_wall_contacts = 0, cold_wall_contacts = 0;  // 0: no heat path through that wall
  std::size_t floating_particles = 0;  // exchange heat with nothing: kept at their start value
  int newton_iterations = 0;
  int factorizations = 0;      // KLU factorisations or AMG setups
  // Of the steady state: klu or amg.
  thermal::LinearSolverKind linear_solver = thermal::LinearSolverKind::Klu;
  long cg_iterations = 0;      // amg: conjugate-gradient iterations
  double max_residual_W = 0.0;
  bool at_rest = true;         // settled packings: came to rest within settle_time
  std::vector<ModeShare> modes;   // every switched-on mode, registry order
  // Zehner-Schlunder-Bauer at this porosity, for a bed of one solid in a gas (gas_conduction on,
  // constant conductivity): the reference of docs/validation.md. W/(m K).
  std::optional<double> zsb_W_per_mK;
  // The bulk, away from the walls' ordered layers: the particles whose centres lie more than
  // bulk_margin_m (two mean diameters) from both walls. k_bulk = (Q / A) / |dT/dx| with dT/dx
  // the least-squares slope of their steady temperatures against their distance from the hot
  // wall (rattlers left out), and the porosity of the slab between the two margins (the sphere
  // volume inside it, exactly). Empty when fewer than 20 particles lie in that slab.
  double bulk_margin_m = 0.0;
  std::size_t bulk_particles = 0;
  std::optional<double> k_bulk_W_per_mK, porosity_bulk, zsb_bulk_W_per_mK;
  std::vector<double> T_K;        // steady temperatures
};

// The study's walls: the two isothermal walls. Throws SceneError naming the walls when the
// scene does not have exactly two facing isothermal walls at different temperatures.
std::pair<std::size_t, std::size_t> conductivity_walls(const Scene& scene);

// Runs the study on the scene (settling first if it asks for mechanics). Throws SceneError for
// an unsuitable scene, thermal::ThermalSolverError when the steady state fails.
// With `step_log`, the settle's steps are logged (MechanicsStepLog.h).
ConductivityResult run_conductivity_study(const Scene& scene, ProgressReporter& progress,
                                          MechanicsStepLog* step_log = nullptr);

// The area a --pressures pressure acts over, m^2: the piston's pressure_area, else the study's
// cross-section (side walls, else the particles' extent as the scene places them).
double piston_area_m2(const Scene& scene);

// `--pressures`: the scene's one piston (piston = true) loads the bed with each pressure in turn
// (force = pressure x piston_area_m2), the bed re-settles from where the previous load left it
// (mechanics.settle_time and settle_velocity per load), and the steady state is solved on that
// packing, with the piston where it came to rest: one result per pressure, in the given order.
// Throws SceneError without exactly one piston, for mechanics "off" or a negative pressure.
// `stop`, asked after every settle step and after every load, ends the study early (an
// interrupted study): the loads finished so far are returned, a load stopped while settling
// left out.
std::vector<ConductivityResult> run_conductivity_pressure_study(
    const Scene& scene, const std::vector<double>& pressures_Pa, ProgressReporter& progress,
    const std::function<bool()>& stop = nullptr, MechanicsStepLog* step_log = nullptr);

}  // namespace tmdem::coupling
