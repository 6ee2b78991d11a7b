#pragma once
// The contacts of a packing that does not move (effects.mechanics = "off"), for the thermal
// network: the touching pairs of the geometry with force 0, except for the particles imported
// with their forces ([[import]] contacts, Scene::imported_forces): their pair contacts and
// normal forces are the file's, and each one resting on a wall (gap <= wall_gap x radius)
// carries the wall force that balances it:
//   F_wall = max(0, -(m g + sum of its pair forces) . n_wall)   (N; n_wall into the domain)
// the pair forces being the file's force vectors (tangential parts included) when it has them,
// else the normal forces along the centre line. Exact for a particle on one wall or on mutually
// perpendicular walls (a box corner); a wall that would pull gets 0.
#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"
#include "mechanics/model/ParticleSet.h"

namespace tmdem::coupling {

// Pairs in the order of find_touching_pairs: particle pairs by (i, j), then walls by (i, wall).
ContactList resting_contacts(const Scene& scene, const mechanics::ParticleSet& particles);

}  // namespace tmdem::coupling
