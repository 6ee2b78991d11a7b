#include "coupling/scene/SceneLimits.h"

#include <cmath>

#include "coupling/common/ShortestNumber.h"
#include "coupling/scene/SceneError.h"
#include "mechanics/ParticleSet.h"

namespace tmdem::coupling {
namespace {

std::string number(double value) { return shortest_number(value); }

// Rough bytes per frame of the XDMF text (one grid of about 1.8 kB per frame).
constexpr double kXdmfBytesPerFrame = 1800.0;
// Contacts per particle in a packing (coordination about 6, each contact counted once).
constexpr double kContactsPerParticle = 3.0;
// pair (16) + normal (8) + tangential (24) + conductance (8) bytes per stored contact.
constexpr double kBytesPerContact = 56.0;

}  // namespace

SceneResources estimate_resources(const Scene& scene) {
  SceneResources r;
  const double n = static_cast<double>(scene.particles.size());
  // Frames at 0, interval, 2 interval, ... below the end, plus the end (CoupledRun).
  r.frames = std::floor(scene.duration_s / scene.output.interval_s) + 2.0;
  if (scene.effects.mechanics == MechanicsMode::Dynamic)
    r.mechanics_steps = std::ceil(scene.duration_s / scene.mechanics.time_step_s);
  const double frame_bytes = n * 7.0 * 8.0 + 4.0 * 8.0;  // position, velocity, temperature
  const double contact_bytes =
      scene.output.contacts ? kContactsPerParticle * n * kBytesPerContact : 0.0;
  r.output_bytes = r.frames * (frame_bytes + contact_bytes + kXdmfBytesPerFrame) + n * 28.0;
  // Mechanics and thermal state, contact lists and the Newton matrix: about 2 kB per particle;
  // the XDMF text and frame times are held in memory once.
  r.memory_bytes = n * 2048.0 + r.frames * (kXdmfBytesPerFrame + 8.0);
  return r;
}

void check_scene_limits(const Scene& scene, const std::vector<std::string>& origins,
                        const std::string& source) {
  const std::string at = source + ": ";
  const SceneResources r = estimate_resources(scene);
  const std::string span = "simulation.duration = " + number(scene.duration_s) +
                           " s with output.interval = " + number(scene.output.interval_s) + " s";
  if (!(r.frames <= kMaxFrames)) {
    throw SceneError(at + span + " gives " + number(r.frames) + " frames; at most " +
                     number(kMaxFrames) + " are allowed (raise output.interval or shorten "
                     "simulation.duration)");
  }
  if (!(r.mechanics_steps <= kMaxMechanicsSteps)) {
    throw SceneError(at + "simulation.duration = " + number(scene.duration_s) +
                     " s with mechanics.time_step = " + number(scene.mechanics.time_step_s) +
                     " s gives " + number(r.mechanics_steps) + " mechanics steps; at most " +
                     number(kMaxMechanicsSteps) + " are allowed");
  }
  if (!(r.output_bytes <= kMaxOutputBytes)) {
    throw SceneError(at + span + " and " + std::to_string(scene.particles.size()) +
                     " particles give an estimated output of " + number(r.output_bytes) +
                     " bytes; at most " + number(kMaxOutputBytes) +
                     " are allowed (raise output.interval, or set output.contacts = false)");
  }
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const Particle& p = scene.particles[i];
    const Material& m = scene.materials[static_cast<std::size_t>(p.material)];
    const double mass_kg = mechanics::sphere_mass(p.radius_m, m.density_kg_per_m3);
    const double capacity_J_per_K = mass_kg * m.heat_capacity_J_per_kgK;
    if (std::isnormal(mass_kg) && std::isnormal(capacity_J_per_K)) continue;
    const std::string key = (i < origins.size() ? origins[i] : "particle " + std::to_string(i)) +
                            ".radius";
    throw SceneError(at + key + ": radius " + number(p.radius_m) + " m gives particle " +
                     std::to_string(i) + " a mass of " + number(mass_kg) +
                     " kg and a heat capacity of " + number(capacity_J_per_K) +
                     " J/K (material[" + std::to_string(p.material) + "] \"" + m.name +
                     "\"): too small to represent; use a larger radius");
  }
}

}  // namespace tmdem::coupling
