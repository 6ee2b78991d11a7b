#include "thermal/modes/ConductanceLaw.h"

#include <algorithm>
#include <cmath>

namespace tmdem::thermal {

double hertz_contact_radius_m(const ContactBody& b1, const ContactBody& b2, double normal_force_N,
                              double flattening) {
  if (!(normal_force_N > 0.0)) return 0.0;
  const double inv_R = 1.0 / b1.radius_m + 1.0 / b2.radius_m;  // 1/inf = 0 for walls
  const double inv_E = (1.0 - b1.poisson_ratio * b1.poisson_ratio) / b1.young_modulus_Pa +
                       (1.0 - b2.poisson_ratio * b2.poisson_ratio) / b2.young_modulus_Pa;
  const double R_star = 1.0 / inv_R;
  const double E_star = 1.0 / inv_E;
  return std::max(std::cbrt(3.0 * normal_force_N * R_star / (4.0 * E_star)), flattening * R_star);
}

double hertz_conductance_W_per_K(const ContactBody& b1, const ContactBody& b2,
                                 double normal_force_N, double flattening) {
  const double k1 = b1.conductivity_W_per_mK, k2 = b2.conductivity_W_per_mK;
  const double k = (k1 + k2 > 0.0) ? 2.0 * k1 * k2 / (k1 + k2) : 0.0;
  return 2.0 * k * hertz_contact_radius_m(b1, b2, normal_force_N, flattening);
}

bool conductance_law_uses_force(ConductanceLawKind law) { return law != ConductanceLawKind::Constant; }

}  // namespace tmdem::thermal
