#include "coupling/bridge/RestingContacts.h"

#include <algorithm>
#include <tuple>

#include "coupling/bridge/SceneToMechanics.h"
#include "mechanics/detection/TouchingPairs.h"

namespace tmdem::coupling {

ContactList resting_contacts(const Scene& scene, const mechanics::ParticleSet& particles) {
  const auto walls = make_mechanics_walls(scene);
  const auto& imported = scene.imported_forces;
  std::vector<std::tuple<std::int64_t, std::int64_t, double>> pairs, wall_pairs;
  // The geometry's pairs, but for two particles whose contacts the file gives.
  for (const auto& p : mechanics::find_touching_pairs(particles, walls, 1e-9)) {
    if (mechanics::is_wall(p.j)) {
      if (!imported.imported(std::size_t(p.i))) wall_pairs.emplace_back(p.i, p.j, 0.0);
    } else if (!imported.imported(std::size_t(p.i)) || !imported.imported(std::size_t(p.j))) {
      pairs.emplace_back(p.i, p.j, 0.0);
    }
  }
  if (!imported.wall_gap.empty()) {
    // Each imported particle's load: its weight plus its pair forces, N.
    const auto& g = scene.gravity_m_per_s2;
    std::vector<Eigen::Vector3d> load(particles.size(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (imported.imported(i)) load[i] = particle_mass_kg(scene, i) * Eigen::Vector3d(g[0], g[1], g[2]);
    for (const auto& c : imported.pairs) {
      pairs.emplace_back(std::int64_t(c.i), std::int64_t(c.j), c.normal_force_N);
      const Eigen::Vector3d f(c.force_on_i_N[0], c.force_on_i_N[1], c.force_on_i_N[2]);
      load[c.i] += f;
      load[c.j] -= f;
    }
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (!imported.imported(i)) continue;
      const auto& x = particles.position[i];
      for (std::size_t w = 0; w < walls.size(); ++w)
        if (walls[w].signed_distance(x) - particles.radius[i] <= imported.wall_gap[i] * particles.radius[i])
          wall_pairs.emplace_back(std::int64_t(i), mechanics::wall_code<std::int64_t>(w),
                                  std::max(0.0, -load[i].dot(walls[w].normal_at(x))));
    }
  }
  const auto by_pair = [](const auto& a, const auto& b) {
    return std::pair(std::get<0>(a), std::get<1>(a)) < std::pair(std::get<0>(b), std::get<1>(b));
  };
  std::sort(pairs.begin(), pairs.end(), by_pair);
  // Walls by (i, wall): wall codes count down from -1.
  std::sort(wall_pairs.begin(), wall_pairs.end(), [](const auto& a, const auto& b) {
    return std::pair(std::get<0>(a), -std::get<1>(a)) < std::pair(std::get<0>(b), -std::get<1>(b));
  });
  ContactList contacts;
  for (const auto* list : {&pairs, &wall_pairs})
    for (const auto& [i, j, force_N] : *list) contacts.add(i, j, force_N);
  return contacts;
}

}  // namespace tmdem::coupling
