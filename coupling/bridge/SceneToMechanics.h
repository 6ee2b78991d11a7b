#pragma once
// Hands the mechanics module the parts of a scene it needs (it never sees the Scene type).
#include <memory>
#include <vector>

#include "coupling/scene/Scene.h"
#include "mechanics/model/Material.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/integrator/NscdParameters.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/model/Wall.h"

namespace tmdem::coupling {

mechanics::ParticleSet make_particle_set(const Scene& scene);
std::vector<mechanics::Material> make_mechanics_materials(const Scene& scene);
std::vector<mechanics::Wall> make_mechanics_walls(const Scene& scene);
mechanics::NscdParameters make_nscd_parameters(const Scene& scene);
// The scene's NSCD integrator over `particles` (the scene's own, or restored from a checkpoint).
std::unique_ptr<mechanics::NscdIntegrator> make_nscd_integrator(const Scene& scene,
                                                                mechanics::ParticleSet particles);
// Puts the points of the mechanics' walls (pistons move) back into scene.walls, so that what
// reads wall geometry from the scene (gaps to walls, the study's length) sees them where they are.
void move_scene_walls(Scene& scene, const std::vector<mechanics::Wall>& walls);
// Solid sphere mass, kg: particles are spheres in 2D runs too.
double particle_mass_kg(const Scene& scene, std::size_t id);

}  // namespace tmdem::coupling
