#include "thermal/modes/KirchhoffContactFlow.h"

#include <algorithm>
#include <cmath>

namespace tmdem::thermal {

ContactFlow kirchhoff_contact_flow(double two_a_m, const PiecewiseLinearTable& k1, double T1,
                                   const PiecewiseLinearTable& k2, double T2) {
  ContactFlow out;
  if (&k1 == &k2) {  // one material: the spot sits at the mean of theta, Q = 2a dtheta
    out.W = two_a_m * (k1.integral(T1) - k1.integral(T2));
    out.dW_dT1 = two_a_m * k1(T1);
    out.dW_dT2 = -two_a_m * k1(T2);
    return out;
  }
  // Spot temperature: F(T) = theta_1(T) + theta_2(T) - target = 0, F' = k_1 + k_2 > 0, root
  // between T1 and T2. Newton from the constant-k guess, kept inside the bracket (bisection
  // when a step leaves it); F is piecewise quadratic, so Newton ends in a few steps.
  const double target = k1.integral(T1) + k2.integral(T2);
  double lo = std::min(T1, T2), hi = std::max(T1, T2);
  const double ka = k1(T1), kb = k2(T2);
  double Tc = (ka * T1 + kb * T2) / (ka + kb);
  for (int it = 0; it < 100 && hi > lo; ++it) {
    const double F = k1.integral(Tc) + k2.integral(Tc) - target;
    if (F == 0.0) break;
    (F > 0.0 ? hi : lo) = Tc;
    double next = Tc - F / (k1(Tc) + k2(Tc));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - Tc) <= 1e-15 * std::abs(Tc)) {
      Tc = next;
      break;
    }
    Tc = next;
  }
  const double k1c = k1(Tc), k2c = k2(Tc);
  // The form that is exact for constant k: 4a (theta_1(T1) - theta_1(Tc)) with Tc from the
  // root; both sides of the balance agree to the root's accuracy.
  out.W = 2.0 * two_a_m * (k1.integral(T1) - k1.integral(Tc));
  out.dW_dT1 = 2.0 * two_a_m * k1(T1) * k2c / (k1c + k2c);
  out.dW_dT2 = -2.0 * two_a_m * k2(T2) * k1c / (k1c + k2c);
  return out;
}

}  // namespace tmdem::thermal
