#include "coupling/app/RunEndReport.h"

#include <algorithm>
#include <limits>

namespace tmdem::coupling {

void print_run_end(const RunSummary& summary, const Scene& scene, const std::string& wrote_path,
                   bool quiet, std::ostream& out) {
  if (!quiet && !wrote_path.empty())
    out << "wrote " << wrote_path << " (" << summary.wall_time_s
        << " s wall time, energy balance error " << summary.energy.balance_error_rel << ")\n";
  const auto& m = summary.mechanics;
  if (!quiet && m.steps > 0) {
    double r_min_m = std::numeric_limits<double>::infinity();
    for (const auto& p : scene.particles) r_min_m = std::min(r_min_m, p.radius_m);
    out << "mechanics: " << m.steps << " steps, mean " << m.mean_iterations << " iterations, "
        << m.unconverged_steps << " unconverged (" << m.stalled_steps
        << " stalled), largest penetration " << m.max_penetration_m << " m";
    if (r_min_m > 0.0 && r_min_m < std::numeric_limits<double>::infinity())
      out << " (" << 100.0 * m.max_penetration_m / r_min_m << "% of the smallest radius)";
    out << "\n";
  }
  // A run interrupted while settling froze nothing: it stopped before t = 0.
  const bool stopped_settling = summary.status == "interrupted" && summary.simulated_time_s == 0.0;
  if (summary.settle && !summary.settle->at_rest && !stopped_settling) {
    out << "warning: the packing was frozen WITHOUT coming to rest: largest speed "
        << summary.settle->max_speed_m_s << " m/s after " << summary.settle->time_s << " s ("
        << summary.settle->steps << " steps), above mechanics.settle_velocity = "
        << scene.mechanics.settle_velocity_m_per_s
        << " m/s; raise mechanics.settle_time or check the contact solver\n";
  }
  out.flush();
}

}  // namespace tmdem::coupling
