#include "coupling/bridge/SceneToMechanics.h"

namespace tmdem::coupling {

double particle_mass_kg(const Scene& scene, std::size_t id) {
  const auto& p = scene.particles[id];
  return mechanics::sphere_mass(p.radius_m, scene.materials[p.material].density_kg_per_m3);
}

mechanics::ParticleSet make_particle_set(const Scene& scene) {
  mechanics::ParticleSet set;
  set.box = periodic_box(scene.periodic);
  set.reserve(scene.particles.size());
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const auto& p = scene.particles[i];
    set.add(Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]), p.radius_m,
            particle_mass_kg(scene, i), p.material, p.fixed);
  }
  return set;
}

std::vector<mechanics::Material> make_mechanics_materials(const Scene& scene) {
  std::vector<mechanics::Material> out;
  for (const auto& m : scene.materials)
    out.push_back({m.density_kg_per_m3, m.young_modulus_Pa, m.poisson_ratio, m.friction,
                   m.rolling_friction});
  return out;
}

std::vector<mechanics::Wall> make_mechanics_walls(const Scene& scene) {
  std::vector<mechanics::Wall> out;
  for (const auto& w : scene.walls) {
    const Eigen::Vector3d point(w.point_m[0], w.point_m[1], w.point_m[2]);
    const Eigen::Vector3d direction(w.normal[0], w.normal[1], w.normal[2]);
    out.push_back(w.cylinder ? mechanics::Wall::cylinder(point, direction, w.radius_m, w.material)
                             : mechanics::Wall::through(point, direction, w.material));
    if (w.piston) out.back().make_piston(w.piston_mass_kg, w.piston_force_N);
  }
  return out;
}

void move_scene_walls(Scene& scene, const std::vector<mechanics::Wall>& walls) {
  for (std::size_t w = 0; w < scene.walls.size() && w < walls.size(); ++w)
    for (int k = 0; k < 3; ++k) scene.walls[w].point_m[k] = walls[w].point[k];
}

mechanics::NscdParameters make_nscd_parameters(const Scene& scene) {
  mechanics::NscdParameters p;
  p.time_step = scene.mechanics.time_step_s;
  p.theta = scene.mechanics.theta;
  p.solver = scene.mechanics.solver;
  p.tolerance = scene.mechanics.tolerance;
  p.fall_tolerance = scene.mechanics.fall_tolerance;
  p.fall_speed = scene.mechanics.fall_speed_m_per_s;
  p.fall_share = scene.mechanics.fall_share;
  p.compaction_speed = scene.mechanics.compaction_speed_m_per_s;
  p.tighten_steps = scene.mechanics.tighten_steps;
  p.stop_travel_fraction = scene.mechanics.stop_travel;
  p.skip_out_of_reach = scene.mechanics.skip_out_of_reach;
  p.estimate_wall_reach = scene.mechanics.estimate_piston_reach;
  p.static_warm_start = scene.mechanics.static_warm_start;
  p.static_balance_rounds = scene.mechanics.static_balance_rounds;
  p.max_iterations = scene.mechanics.max_iterations;
  p.retry_parts = scene.mechanics.retry_parts;
  p.retry_keep_steps = scene.mechanics.retry_keep_steps;
  p.fallback_on_last_try = scene.mechanics.fallback_on_last_try;
  p.full_sweep_every = scene.mechanics.full_sweep_every;
  p.siconos_stop = scene.mechanics.stop_test == "siconos";
  p.residual_check_every = scene.mechanics.residual_check_every;
  p.normal_law = scene.mechanics.normal_law;
  p.penetration_slop_fraction = scene.mechanics.penetration_slop;
  p.recovery_speed = scene.mechanics.recovery_speed_m_per_s;
  return p;
}

}  // namespace tmdem::coupling

namespace tmdem::coupling {

std::unique_ptr<mechanics::NscdIntegrator> make_nscd_integrator(const Scene& scene,
                                                                mechanics::ParticleSet particles) {
  const auto& g = scene.gravity_m_per_s2;
  const std::size_t count = particles.size();
  auto integrator = std::make_unique<mechanics::NscdIntegrator>(
      std::move(particles), make_mechanics_materials(scene), make_mechanics_walls(scene),
      Eigen::Vector3d(g[0], g[1], g[2]), scene.dimension, make_nscd_parameters(scene));
  // [[import]] overlaps = "hold" (the default): the overlaps an import brought are its
  // packing's, held by the position step (NscdIntegrator::hold_initial_overlaps). A "hertz"
  // law reads every overlap as elastic: nothing is held there.
  if (count == scene.particles.size() && scene.mechanics.normal_law != mechanics::NormalLaw::hertz) {
    std::vector<std::uint8_t> holds(count, 0);
    bool any = false;
    for (const ImportReport& i : scene.imports) {
      if (!i.hold_overlaps || !(i.largest_overlap > 0.0)) continue;
      std::fill_n(holds.begin() + std::ptrdiff_t(i.first_id), i.count, std::uint8_t{1});
      any = true;
    }
    if (any) integrator->hold_initial_overlaps(std::move(holds));
  }
  return integrator;
}

}  // namespace tmdem::coupling
