#include "coupling/ContactRecording.h"

#include <chrono>

#include "coupling/SceneToMechanics.h"
#include "coupling/ThermalProblem.h"

namespace tmdem::coupling {

ContactRecording record_contacts(const Scene& scene, ProgressReporter& progress) {
  const auto start = std::chrono::steady_clock::now();
  mechanics::NscdIntegrator nscd(
      make_particle_set(scene), make_mechanics_materials(scene), make_mechanics_walls(scene),
      Eigen::Vector3d(scene.gravity_m_per_s2[0], scene.gravity_m_per_s2[1],
                      scene.gravity_m_per_s2[2]),
      scene.dimension, make_nscd_parameters(scene));
  ContactRecording rec;
  const double h = scene.mechanics.time_step_s;
  double t = 0.0;
  for (long k = 1; t < scene.duration_s - 1e-9 * h; ++k) {
    const double t_next = std::min(double(k) * h, scene.duration_s);
    nscd.step(t_next - t);
    t = t_next;
    rec.step_end_s.push_back(t);
    rec.contacts.emplace_back();
    gather_contacts(nscd.contacts(), rec.contacts.back());
    progress.update("mechanics", t, scene.duration_s,
                    std::to_string(rec.contacts.back().size()) + " contacts");
  }
  progress.done();
  rec.mechanics_wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return rec;
}

}  // namespace tmdem::coupling
