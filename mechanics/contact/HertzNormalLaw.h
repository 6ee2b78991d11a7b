#pragma once
// The Hertz normal law of two elastic spheres (or a sphere and a plane wall) as NSCD sees it:
// F = K delta^(3/2), K = (4/3) E* sqrt(R*), delta the overlap (m), with
//   1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j  and  1/R* = 1/R_i + 1/R_j (a wall: R* = R_i).
// The contact radius is a = sqrt(R* delta) = (3 F R* / (4 E*))^(1/3), the one the thermal
// module's Hertz conductance takes from the force: at rest both agree.
//
// Inside a Moreau-Jean step the law is linearised about a tangent overlap delta* (the
// force the pair carried last step, or more; MechanicsNormalLaw.h), stiffness
// k = dF/d delta = (3/2) K sqrt(delta*), F* = K delta*^(3/2) = (2/3) k delta*. With the end-of-step overlap
// delta+ = -(g~ + h u_n) (g~ the step's predicted gap, u_n the new normal velocity) and the
// normal impulse r_n = h F(delta+) ~= h (F* + k (delta+ - delta*)), the contact obeys
//   u_n + (g~ + delta*/3) / h + r_n / (k h^2) >= 0,  r_n >= 0,  complementary:
// the rigid contact's condition with bias (g~ + delta*/3)/h and compliance 1/(k h^2)
// (ContactProblem::compliance). The tangent line crosses zero force at delta*/3: the contact
// engages there, and at rest (delta+ = delta*, r_n = h F*) the force is Hertz's exactly.

#include <cmath>

namespace tmdem::mechanics {

// E*, Pa, of two materials (Young's modulus E > 0 Pa, Poisson's ratio nu in [0, 0.5]).
inline double hertz_effective_modulus(double young_i_Pa, double poisson_i, double young_j_Pa,
                                      double poisson_j) {
  return 1.0 / ((1.0 - poisson_i * poisson_i) / young_i_Pa + (1.0 - poisson_j * poisson_j) / young_j_Pa);
}

// R*, m, of two radii (radius_j 0: a plane wall, R* = radius_i).
inline double hertz_effective_radius(double radius_i_m, double radius_j_m) {
  return radius_j_m > 0.0 ? radius_i_m * radius_j_m / (radius_i_m + radius_j_m) : radius_i_m;
}

// K = (4/3) E* sqrt(R*), N/m^(3/2).
inline double hertz_coefficient(double effective_modulus_Pa, double effective_radius_m) {
  return 4.0 / 3.0 * effective_modulus_Pa * std::sqrt(effective_radius_m);
}

// F = K delta^(3/2), N (0 for no overlap).
inline double hertz_force(double coefficient, double overlap_m) {
  return overlap_m > 0.0 ? coefficient * overlap_m * std::sqrt(overlap_m) : 0.0;
}

// The overlap carrying force F: delta = (F / K)^(2/3), m.
inline double hertz_overlap(double coefficient, double force_N) {
  return force_N > 0.0 ? std::cbrt((force_N / coefficient) * (force_N / coefficient)) : 0.0;
}

// The step's linear law about delta* (> 0): compliance 1/(k h^2) (1/kg) and bias (m/s).
struct HertzStepLaw {
  double compliance_per_kg = 0.0;
  double bias_m_per_s = 0.0;
};
inline HertzStepLaw hertz_step_law(double coefficient, double tangent_overlap_m, double predicted_gap_m,
                                   double h_s) {
  const double stiffness_N_per_m = 1.5 * coefficient * std::sqrt(tangent_overlap_m);
  return {1.0 / (stiffness_N_per_m * h_s * h_s), (predicted_gap_m + tangent_overlap_m / 3.0) / h_s};
}

}  // namespace tmdem::mechanics
