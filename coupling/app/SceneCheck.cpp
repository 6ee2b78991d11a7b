#include "coupling/app/SceneCheck.h"

#include <algorithm>
#include <cmath>

#include "coupling/app/StepTravel.h"
#include "coupling/bridge/ContactList.h"
#include "coupling/bridge/RestingContacts.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/ParticleImport.h"
#include "coupling/scene/SceneLimits.h"
#include "mechanics/detection/TouchingPairs.h"
#include "thermal/integrators/MpiWorld.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

namespace {
const char* mechanics_name(MechanicsMode m) {
  switch (m) {
    case MechanicsMode::Off: return "off";
    case MechanicsMode::Settle: return "settle";
    case MechanicsMode::Dynamic: return "dynamic";
    case MechanicsMode::Coupled: return "coupled";
  }
  return "?";
}
}  // namespace

void check_scene(const Scene& scene, std::ostream& out) {
  const std::size_t n = scene.particles.size();
  double r_min = n ? scene.particles[0].radius_m : 0.0, r_max = r_min;
  double T_min = n ? scene.particles[0].temperature_K : 0.0, T_max = T_min;
  std::size_t held = 0, sources = 0, fixed = 0;
  for (const auto& p : scene.particles) {
    r_min = std::min(r_min, p.radius_m);
    r_max = std::max(r_max, p.radius_m);
    T_min = std::min(T_min, p.temperature_K);
    T_max = std::max(T_max, p.temperature_K);
    held += p.fixed_temperature;
    sources += p.heat_source_W != 0.0;
    fixed += p.fixed;
  }
  out << "scene: " << scene.source << " (" << scene.dimension << "D, duration "
      << scene.duration_s << " s)\n";
  out << "particles: " << n << ", radius " << r_min << " .. " << r_max << " m, temperature "
      << T_min << " .. " << T_max << " K; " << held << " held, " << sources
      << " with heat sources, " << fixed << " fixed\n";
  for (const auto& report : scene.imports) out << describe_import(report) << "\n";
  for (const auto& warning : scene.warnings) out << "warning: " << warning << "\n";
  out << "materials:";
  for (const auto& m : scene.materials) out << " " << m.name;
  out << "\nwalls: " << scene.walls.size();
  std::size_t isothermal = 0;
  for (const auto& w : scene.walls) isothermal += w.temperature_K.has_value();
  out << " (" << isothermal << " isothermal)\n";
  if (scene.periodic.any()) {
    out << "periodic:";
    const char* separator = " ";
    for (int a = 0; a < 3; ++a)
      if (scene.periodic.axis[std::size_t(a)]) {
        out << separator << "xyz"[a] << " [" << scene.periodic.low_m[std::size_t(a)] << ", "
            << scene.periodic.high_m[std::size_t(a)] << ") m";
        separator = ", ";
      }
    out << "\n";
  }
  out << "effects: mechanics " << mechanics_name(scene.effects.mechanics);
  for (const auto& e : thermal::heat_transfer_effects())
    out << ", " << e.key << (scene.effects.on(e.key) ? " on" : " off");
  out << "\n";
  const SceneResources resources = estimate_resources(scene);
  out << "estimated output: " << resources.frames << " frames, about "
      << resources.output_bytes / 1e6 << " MB (result file and XDMF"
      << (scene.output.contacts ? ", contacts estimated at 3 per particle" : "")
      << "); memory about " << resources.memory_bytes / 1e6 << " MB\n";
  // The pairs touching now: the travel estimate's resting particles and the network's contacts
  // below (one search for both; the network of an imported bed without mechanics takes the
  // imported forces instead, and the travel estimate is not made without mechanics).
  const auto particles = make_particle_set(scene);
  const bool network_from_imports =
      scene.effects.mechanics == MechanicsMode::Off && !scene.imported_forces.wall_gap.empty();
  const std::vector<mechanics::TouchingPair> touching =
      network_from_imports ? std::vector<mechanics::TouchingPair>{}
                           : mechanics::find_touching_pairs(particles, make_mechanics_walls(scene),
                                                                           kRestingOverlapFraction);
  const StepTravel travel = estimate_step_travel(scene, touching);
  if (travel.resting_particles > 0)
    out << "mechanics: " << travel.resting_particles
        << " particles rest at the start on what is below them (a laid or imported bed): no fall estimated for them\n";
  if (travel.speed_m_per_s > 0.0) {
    out << "mechanics: largest speed estimated " << travel.speed_m_per_s
        << " m/s (gravity and pistons; coupling/app/StepTravel.h), " << travel.travel_m
        << " m per step = " << travel.travel_m / travel.smallest_radius_m
        << " of the smallest radius (limit " << travel.fraction << ")\n";
    if (travel.too_far()) {
      const bool dynamic = scene.effects.mechanics == MechanicsMode::Dynamic;
      out << "warning: a particle can move more than " << travel.fraction
          << " of the smallest radius per step (" << travel.travel_m << " m against "
          << travel.smallest_radius_m << " m): contact normals and gaps are frozen over a step, "
          << "so a contact can carry force while its particles are still up to "
          << travel.ghost_gap_m() << " m apart"
          << (dynamic ? ", and conduct heat there"
                      : ", and a particle can be stopped by a neighbour it would not reach")
          << "; lower mechanics.time_step below " << travel.limit_m() / travel.speed_m_per_s
          << " s\n";
    }
  }
  if (travel.speed_m_per_s > 0.0 && scene.periodic.any()) {
    // The detector's look-ahead across the periods, 2 h (|v| + h |g|) of the velocity's and
    // gravity's parts along the periodic axes, must fit twice in half the shortest period less
    // the largest diameter (mechanics/detection/ContactDetector.h), else the run stops. The
    // speed estimated is a fall along gravity or a piston's stroke along its normal: each
    // counts by its share along the periodic axes (a bed pressed or poured along its walled
    // axis moves hardly across the periods).
    const mechanics::PeriodicBox box = periodic_box(scene.periodic);
    double r_max = 0.0;
    for (const auto& p : scene.particles) r_max = std::max(r_max, p.radius_m);
    const auto across = [&box](const Vec3& x) { return box.norm_across(Eigen::Vector3d(x[0], x[1], x[2])); };
    const double h = scene.mechanics.time_step_s;
    const double g = std::hypot(scene.gravity_m_per_s2[0], scene.gravity_m_per_s2[1], scene.gravity_m_per_s2[2]);
    double share = g > 0.0 ? across(scene.gravity_m_per_s2) / g : 0.0;
    for (const auto& w : scene.walls)
      if (w.piston) share = std::max(share, across(w.normal));
    const double needed_m = 4.0 * h * (share * travel.speed_m_per_s + h * across(scene.gravity_m_per_s2));
    const double room_m = 0.5 * box.shortest_period() - 2.0 * r_max;
    if (needed_m > room_m)
      out << "warning: at the estimated speed the detection needs " << needed_m
          << " m of margin (twice the look-ahead across the periods), more than the periods leave (" << room_m
          << " m: half the shortest period less the largest diameter); the run would stop when a "
             "particle gets that fast: enlarge the period or lower mechanics.time_step\n";
  }
  out << "thermal: integrator " << scene.thermal.integrator << ", conductance "
      << thermal::name_of(scene.thermal.conductance) << "\n";

  // Estimated network on the contacts present now.
  ContactList contacts;
  const double g = std::hypot(scene.gravity_m_per_s2[0], scene.gravity_m_per_s2[1],
                              scene.gravity_m_per_s2[2]);
  // Without mechanics, forces imported with the packing are the run's own: no estimate.
  if (network_from_imports)
    contacts = resting_contacts(scene, particles);
  else
    for (const auto& p : touching) contacts.add(p.i, p.j, particles.mass[std::size_t(p.i)] * g);
  const auto system = build_thermal_system(scene, contacts, &particles);
  out << "modes:";
  for (const auto& mode : system->modes()) out << " " << mode->name();
  out << "\n";
  // The solver the run will take (it resolves "auto" the same way, on the same system); the
  // explicit update solves no linear system.
  if (thermal::parse_integrator_kind(scene.thermal.integrator) !=
      thermal::IntegratorKind::Explicit) {
    const auto solver = choose_linear_solver(scene, *system, thermal::MpiWorld::size());
    out << "linear solver " << solver.name() << " (" << solver.reason << ")\n";
    if (const auto warning = klu_size_warning({scene.thermal.linear_solver, n, scene.dimension, 1,
                                               system->symmetric_jacobian()});
        !warning.empty())
      out << "warning: " << warning << "\n";
  }
  out << "estimated stiffness on the " << contacts.size() << " contacts touching at start"
      << (scene.effects.mechanics != MechanicsMode::Off &&
                  thermal::conductance_law_uses_force(scene.thermal.conductance)
              ? " (Hertz force estimated as each particle's weight; settling gives the real one)"
              : "")
      << ":\n";
  print_diagnostics(out, diagnose(scene, contacts, *system, max_scene_temperature_K(scene)));
}

}  // namespace tmdem::coupling
