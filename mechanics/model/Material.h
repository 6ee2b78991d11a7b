#pragma once
// Mechanical properties of one material. Thermal properties live in thermal/; the coupling
// keeps one list of materials and hands each module the fields it needs, by the same index.

#include <algorithm>

namespace tmdem::mechanics {

struct Material {
  double density = 0.0;        // kg/m^3
  double young_modulus = 0.0;  // Pa (not used by the rigid NSCD contact law; kept for Hertz)
  double poisson_ratio = 0.0;  // -
  double friction = 0.0;       // Coulomb coefficient, >= 0
  // Rolling resistance coefficient mu_r, dimensionless, >= 0: a contact resists rolling with
  // an angular impulse up to mu_r R_eff r_n (ContactProblem.h). 0: rolls freely.
  double rolling_friction = 0.0;
};

// Friction coefficient of a contact between two materials: the smaller of the two.
// Why: with no tribological data for the pair, the weaker surface limits the tangential
// force; this is also symmetric and reduces to the material's own value for like pairs.
inline double contact_friction(const Material& a, const Material& b) {
  return std::min(a.friction, b.friction);
}

// Rolling resistance coefficient of a contact: the smaller of the two, as for friction.
inline double contact_rolling_friction(const Material& a, const Material& b) {
  return std::min(a.rolling_friction, b.rolling_friction);
}

}  // namespace tmdem::mechanics
