#pragma once
// The pieces of a run that turn a scene into a thermal problem, shared by `tmdem run` and
// `tmdem study accuracy`: settling, the canonical contact list, the thermal system with the
// modes the scene switches on, and the integrator settings.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/output/RunSummary.h"
#include "coupling/run/MechanicsStepLog.h"
#include "coupling/run/SettleProgress.h"
#include "coupling/scene/Scene.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "mechanics/contact/ContactForce.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

// Steps the NSCD integrator until the rest test of mechanics.rest_test is met ("network": the
// normal forces stationary and the load carriers still, SettleRestTest.h; "velocity": every
// particle slower than mechanics.settle_velocity) or mechanics.settle_time runs out (then a
// warning with the figures). Returns how it ended: at rest or not, by which test, the settle
// time and steps used, the largest speed and the rattlers when frozen. `stop`, asked
// after every step, ends settling early (an interrupted run): at_rest is then false and no
// "not at rest" warning is printed. `state`, when given, is where the settle stands: read at
// the start (a settle resumed from a settle checkpoint, whose integrator state `nscd` already
// holds; a default SettleProgress starts afresh) and written at the end, so that a settle
// stopped early can be checkpointed and resumed bit for bit (SettleProgress.h).
// `checkpoints`, when given, is asked after every step whether a settle checkpoint is due, and
// then handed where the settle stands (a run's periodic settle checkpoints).
struct SettleCheckpoints {
  std::function<bool()> due;
  std::function<void(const SettleProgress&)> write;
};
SettleSummary settle_packing(mechanics::NscdIntegrator& nscd, const Scene& scene,
                             ProgressReporter& progress,
                             const std::function<bool()>& stop = nullptr,
                             SettleProgress* state = nullptr,
                             const SettleCheckpoints* checkpoints = nullptr);

// "warning: <what> at t = ... s: contact solver <name> did not converge ..." for an unconverged
// (or stalled) step; shared by settle and dynamic runs so both name the solver in use.
std::string unconverged_step_warning(const std::string& what, double t_s,
                                     const mechanics::NscdIntegrator& nscd,
                                     const mechanics::StepReport& report, double tolerance);

// The mechanics' contacts, which arrive in canonical (i, j) order, copied in that order, so that
// the same graph always gives the same edge list and the thermal side can tell a values-only
// change from a new shape. Throws std::logic_error if `forces` is not strictly (i, j)-sorted.
void gather_contacts(const std::vector<mechanics::ContactForce>& forces, ContactList& out);

// Network nodes from the scene, edges from `contacts` (conductances filled in), and the modes
// the scene switches on (a mode that is off is never built). geometry: the frozen packing,
// needed when a mode works across gaps (near pairs); null for a moving packing.
std::unique_ptr<thermal::ThermalSystem> build_thermal_system(
    const Scene& scene, ContactList& contacts, const mechanics::ParticleSet* geometry = nullptr);

// The same nodes and modes with no edge: the whole bed's heat capacities and energy for a
// process over MPI that builds its network from its own piece of the bed (BedPiece.h).
std::unique_ptr<thermal::ThermalSystem> build_thermal_nodes(const Scene& scene);

// Largest temperature the run can see: particles, isothermal walls, fluid, surroundings.
double max_scene_temperature_K(const Scene& scene);

// [thermal] of the scene as integrator settings, with `linear_solver` the scene's resolved
// (choose_linear_solver, LinearSolverChoice.h: the scene's may be "auto").
thermal::IntegratorSettings integrator_settings(const Scene& scene,
                                                thermal::LinearSolverKind linear_solver);

// A scene's thermal problem on a frozen contact graph: contacts from geometry (mechanics off)
// or from settling (settle). Throws std::invalid_argument for a dynamic scene.
struct FrozenThermalProblem {
  ContactList contacts;
  std::optional<SettleSummary> settle;  // settle scenes only
  std::unique_ptr<thermal::ThermalSystem> system;
  std::vector<double> T0_K;
  std::vector<Vec3> positions_m;  // particle centres of the frozen packing (after settling)
  std::vector<Vec3> wall_points_m;  // walls' points (a piston's after settling)
};
// With `step_log`, the settle's steps are logged (phase "settle").
FrozenThermalProblem build_frozen_thermal_problem(const Scene& scene, ProgressReporter& progress,
                                                  MechanicsStepLog* step_log = nullptr);

// The frozen thermal problem of the packing `nscd` holds now (after settle_packing): its
// contacts and positions, and the thermal system built with the walls where the mechanics has
// them (pistons move). Sets everything but `settle`.
void freeze_packing(const Scene& scene, const mechanics::NscdIntegrator& nscd,
                    FrozenThermalProblem& problem);

}  // namespace tmdem::coupling
