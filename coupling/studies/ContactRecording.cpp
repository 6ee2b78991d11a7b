#include "coupling/studies/ContactRecording.h"

#include <chrono>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/ThermalProblem.h"

namespace tmdem::coupling {

ContactRecording record_contacts(const Scene& scene, ProgressReporter& progress) {
  const auto start = std::chrono::steady_clock::now();
  auto nscd_ptr = make_nscd_integrator(scene, make_particle_set(scene));
  auto& nscd = *nscd_ptr;
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
