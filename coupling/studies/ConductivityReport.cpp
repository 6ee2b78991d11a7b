#include "coupling/studies/ConductivityReport.h"

#include <iomanip>

#include "coupling/common/ShortestNumber.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

void print_conductivity_report(std::ostream& out, const ConductivityResult& r) {
  out << "hot wall[" << r.hot_wall << "] " << shortest_number(r.T_hot_K) << " K, cold wall["
      << r.cold_wall << "] " << shortest_number(r.T_cold_K) << " K, L = " << r.length_m
      << " m, A = " << r.area_m2 << " m^2"
      << (r.periodic_axes.empty() ? "" : " (periodic along " + r.periodic_axes + ": A from the periods)")
      << "\n"
      << "particles " << r.particles << ", contacts " << r.contacts << " (+ " << r.wall_contacts
      << " with walls), coordination number " << r.coordination << ", porosity " << r.porosity
      << "\n";
  if (r.floating_particles > 0)
    out << r.floating_particles
        << " particles exchange heat with nothing (rattlers): kept at their start temperature\n";
  out << std::setprecision(10) << "heat in through the hot wall " << r.heat_hot_W
      << " W, out through the cold wall " << r.heat_cold_W << " W (relative difference "
      << std::setprecision(3) << r.balance_rel << ")\n"
      << "steady state: " << r.newton_iterations << " Newton iterations, ";
  if (r.linear_solver == thermal::LinearSolverKind::Amg)
    out << r.factorizations << " BoomerAMG setup(s), " << r.cg_iterations << " CG iterations";
  else
    out << r.factorizations << " KLU factorisation(s)";
  out << ", largest residual " << r.max_residual_W << " W\n";
  for (const auto& m : r.modes)
    out << "  " << std::left << std::setw(20) << m.mode << std::right << " share "
        << std::setprecision(6) << m.share << "  (hot wall " << m.hot_wall_W + 0.0 << " W, cold wall "
        << m.cold_wall_W + 0.0 << " W)\n";
  out << std::setprecision(8) << "k_eff = " << r.k_eff_W_per_mK << " W/(m K)\n"
      << std::setprecision(6);
  if (r.zsb_W_per_mK)
    out << "Zehner-Schlunder-Bauer at this porosity (flattening 0.0077, the gas's jump length): "
        << *r.zsb_W_per_mK << " W/(m K), k_eff / ZSB = " << r.k_eff_W_per_mK / *r.zsb_W_per_mK
        << " (docs/validation.md)\n";
  if (r.k_bulk_W_per_mK) {
    out << "bulk (" << r.bulk_particles << " particles more than " << r.bulk_margin_m
        << " m from both walls): porosity " << *r.porosity_bulk << std::setprecision(8)
        << ", k_bulk = " << *r.k_bulk_W_per_mK << " W/(m K)" << std::setprecision(6);
    if (r.zsb_bulk_W_per_mK)
      out << ", ZSB at that porosity " << *r.zsb_bulk_W_per_mK << " W/(m K), k_bulk / ZSB = "
          << *r.k_bulk_W_per_mK / *r.zsb_bulk_W_per_mK;
    out << "\n";
  }
}

void write_conductivity_csv(std::ostream& out, const std::vector<ConductivityResult>& results) {
  out << "pressure_Pa,k_eff_W_per_mK,heat_hot_W,heat_cold_W,balance_rel,porosity,coordination,"
         "length_m,area_m2,T_hot_K,T_cold_K,particles,contacts,wall_contacts,floating_particles";
  const auto modes = thermal::heat_transfer_modes();
  for (const auto* mode : modes) out << ",share_" << mode->name;
  out << ",k_bulk_W_per_mK,porosity_bulk\n";
  for (const auto& r : results) {
    out << (r.pressure_Pa ? shortest_number(*r.pressure_Pa) : std::string()) << ","
        << shortest_number(r.k_eff_W_per_mK) << "," << shortest_number(r.heat_hot_W) << ","
        << shortest_number(r.heat_cold_W) << "," << shortest_number(r.balance_rel) << ","
        << shortest_number(r.porosity) << "," << shortest_number(r.coordination) << ","
        << shortest_number(r.length_m) << "," << shortest_number(r.area_m2) << ","
        << shortest_number(r.T_hot_K) << "," << shortest_number(r.T_cold_K) << "," << r.particles
        << "," << r.contacts << "," << r.wall_contacts << "," << r.floating_particles;
    for (const auto* mode : modes) {
      double share = 0.0;
      for (const auto& m : r.modes)
        if (m.mode == mode->name) share = m.share;
      out << "," << shortest_number(share);
    }
    // Empty where the bed has no bulk to measure (ConductivityResult::k_bulk_W_per_mK).
    out << "," << (r.k_bulk_W_per_mK ? shortest_number(*r.k_bulk_W_per_mK) : std::string()) << ","
        << (r.porosity_bulk ? shortest_number(*r.porosity_bulk) : std::string()) << "\n";
  }
}

}  // namespace tmdem::coupling
