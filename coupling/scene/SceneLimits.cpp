#include "coupling/scene/SceneLimits.h"

#include <cmath>

#include "coupling/common/ShortestNumber.h"
#include "coupling/scene/SceneError.h"
#include "mechanics/model/ParticleSet.h"

namespace tmdem::coupling {
namespace {

std::string number(double value) { return shortest_number(value); }

// "21 GB", "1 GB", "350 MB", "12 kB": two significant figures at most, in the largest unit
// that keeps the figure at least 1.
std::string bytes_text(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB"};
  int u = 0;
  while (u < 4 && bytes >= 1000.0) {
    bytes /= 1000.0;
    ++u;
  }
  const double scale = bytes >= 10.0 ? 1.0 : 10.0;
  return number(std::round(bytes * scale) / scale) + " " + units[u];
}

// Measured on examples, datasets compressed (shuffle + deflate 1), rounded up. Dynamic
// (poured_bed.toml, 80 particles, 21 frames: 0.41 MB + 0.07 MB XDMF): bytes per particle and
// frame: position 17, velocity 17, temperature 6. Frozen (settle or off: paper_bed.toml, 256
// particles, 453 contacts, 101 frames: 0.80 MB + 0.36 MB XDMF): positions, velocities and the
// contacts' pair, forces and conductance are written once (BlockSeries.h); per frame only the
// temperature (4.3 bytes per particle) and the heat flow (6.5 bytes per contact) are new.
constexpr double kMovingBytesPerParticle = 40.0;
constexpr double kFrozenBytesPerParticle = 5.0;
// Contacts per particle in a packing (coordination about 6, each contact counted once).
constexpr double kContactsPerParticle = 3.0;
// A contact row (pair, normal and tangential force, conductance, heat flow; 64 bytes raw)
// compressed, plus 16 bytes of the XDMF line set when the contacts change every frame; frozen:
// the heat flow alone.
constexpr double kMovingBytesPerContact = 56.0;
constexpr double kFrozenBytesPerContact = 8.0;
// HDF5 metadata of a frame's XDMF views (ResultViews.h): virtual datasets of about 1.5 kB
// each; in a frozen bed only temperature and heat_flow are new, the rest are hard links
// (paper_bed.toml: 3.3 kB per frame).
constexpr double kMovingViewBytesPerFrame = 12000.0;
constexpr double kFrozenViewBytesPerFrame = 3500.0;
// XDMF text per frame: the particle grid, the contact grid and the wall grid.
constexpr double kXdmfParticleBytes = 1200.0;
constexpr double kXdmfContactBytes = 1300.0;
constexpr double kXdmfWallBytes = 700.0;

}  // namespace

namespace {

// The estimate of the scene written every interval_s seconds (its own output.interval, or
// another the large-output warning tries: no copy of the scene for it).
SceneResources estimate_resources(const Scene& scene, double interval_s) {
  SceneResources r;
  const double n = static_cast<double>(scene.particles.size());
  // Frames at 0, interval, 2 interval, ... below the end, plus the end (CoupledRun).
  r.frames = std::floor(scene.duration_s / interval_s) + 2.0;
  if (scene.effects.mechanics == MechanicsMode::Dynamic)
    r.mechanics_steps = std::ceil(scene.duration_s / scene.mechanics.time_step_s);
  const bool frozen = scene.effects.mechanics == MechanicsMode::Off ||
                      scene.effects.mechanics == MechanicsMode::Settle;
  const double frame_bytes =
      n * (frozen ? kFrozenBytesPerParticle : kMovingBytesPerParticle) + 4.0 * 8.0;
  const double contact_bytes =
      scene.output.contacts
          ? kContactsPerParticle * n * (frozen ? kFrozenBytesPerContact : kMovingBytesPerContact)
          : 0.0;
  const double view_bytes = frozen ? kFrozenViewBytesPerFrame : kMovingViewBytesPerFrame;
  const double xdmf_bytes = kXdmfParticleBytes +
                            (scene.output.contacts ? kXdmfContactBytes : 0.0) +
                            (scene.walls.empty() ? 0.0 : kXdmfWallBytes);
  // Once: the particles' constants, the XDMF's connectivity and, frozen, the blocks written
  // once (positions and velocities 48 bytes per particle, contacts 64 per contact, raw).
  r.output_bytes = r.frames * (frame_bytes + contact_bytes + view_bytes + xdmf_bytes) +
                   n * (28.0 + 8.0) + 16.0 * kContactsPerParticle * n +
                   (frozen ? n * 48.0 + 64.0 * kContactsPerParticle * n : 0.0);
  // Mechanics and thermal state, contact lists and the Newton matrix: about 2 kB per particle;
  // the XDMF text and frame times are held in memory once.
  r.memory_bytes = n * 2048.0 + r.frames * (xdmf_bytes + 8.0);
  return r;
}

}  // namespace

SceneResources estimate_resources(const Scene& scene) {
  return estimate_resources(scene, scene.output.interval_s);
}

std::string large_output_warning(const Scene& scene, double warn_bytes, double target_bytes) {
  const SceneResources r = estimate_resources(scene);
  if (!(r.output_bytes > warn_bytes)) return {};
  const std::string contacts =
      scene.output.contacts ? "; output.contacts = false leaves the contacts out" : "";
  const std::string said = "simulation.duration = " + number(scene.duration_s) +
                           " s with output.interval = " + number(scene.output.interval_s) +
                           " s gives " + number(r.frames) + " frames of " +
                           std::to_string(scene.particles.size()) +
                           " particles, an estimated output of about " +
                           bytes_text(r.output_bytes) + " (result file and XDMF)";
  // Frames go about as 1 / interval: start from the interval scaled by the estimate over the
  // target, rounded up to 1, 2 or 5 times a power of ten, and go up that ladder until the
  // estimate fits (the first and last frames do not shrink with the interval).
  const double wanted_s = scene.output.interval_s * r.output_bytes / target_bytes;
  const double decade = std::pow(10.0, std::floor(std::log10(wanted_s)));
  for (int rung = 0; rung < 12; ++rung) {
    const double step[] = {1.0, 2.0, 5.0};
    const double suggested_s = step[rung % 3] * decade * std::pow(10.0, rung / 3);
    if (suggested_s < wanted_s) continue;
    if (suggested_s > scene.duration_s) break;  // only the first and last frames are left
    if (estimate_resources(scene, suggested_s).output_bytes <= target_bytes)
      return said + "; output.interval = " + number(suggested_s) + " s gives at most " +
             bytes_text(target_bytes) + contacts;
  }
  return said + "; even its first and last frames pass " + bytes_text(target_bytes) + contacts;
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
