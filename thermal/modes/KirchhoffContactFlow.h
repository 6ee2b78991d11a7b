#pragma once
// Heat flow through a Hertz contact between two bodies whose conductivities follow temperature.
//
// Each body is a half-space feeding a circular spot of radius a, whose constriction conductance
// is 4 k a. With k(T), the Kirchhoff transform theta(T) = int_0^T k(s) ds makes each half-space
// linear in theta, so the spot at temperature T_c carries
//   Q = 4 a (theta_1(T_1) - theta_1(T_c)) = 4 a (theta_2(T_c) - theta_2(T_2)),
// T_c solving theta_1(T_c) + theta_2(T_c) = theta_1(T_1) + theta_2(T_2). For constant k this is
// Q = 2 a (2 k1 k2 / (k1 + k2)) (T_1 - T_2), the constant-property Hertz law (contract section 2);
// for one material it is Q = 2 a (theta(T_1) - theta(T_2)), exact. Derivatives (implicit in T_c):
//   dQ/dT_1 = 4 a k_1(T_1) k_2(T_c) / (k_1(T_c) + k_2(T_c)),
//   dQ/dT_2 = -4 a k_2(T_2) k_1(T_c) / (k_1(T_c) + k_2(T_c)).
#include "thermal/network/PiecewiseLinearTable.h"

namespace tmdem::thermal {

struct ContactFlow {
  double W = 0.0;         // from body 1 into body 2
  double dW_dT1 = 0.0;    // W/K
  double dW_dT2 = 0.0;    // W/K
};

// two_a_m: 2 a (m). k1, k2: conductivity tables, W/(m K) against K (the same object for one
// material, which takes the closed form). Temperatures > 0 K.
ContactFlow kirchhoff_contact_flow(double two_a_m, const PiecewiseLinearTable& k1, double T1_K,
                                   const PiecewiseLinearTable& k2, double T2_K);

// Harmonic mean 2 k1 k2 / (k1 + k2), W/(m K).
inline double harmonic_mean_conductivity(double k1, double k2) { return 2.0 * k1 * k2 / (k1 + k2); }

}  // namespace tmdem::thermal
