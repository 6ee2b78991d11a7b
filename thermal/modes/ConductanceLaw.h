#pragma once
// Contact conductance laws (contract section 2). Walls enter with infinite radius (1/R = 0).
#include <array>
#include <limits>
#include <string_view>

#include "thermal/network/KindName.h"

namespace tmdem::thermal {

// One side of a contact: what the contact laws need to know about a body.
struct ContactBody {
  double radius_m = std::numeric_limits<double>::infinity();  // infinity for a wall
  double conductivity_W_per_mK = 0.0;
  double young_modulus_Pa = 0.0;
  double poisson_ratio = 0.0;
  // Its surface, for the rough-contact law (RoughContactConductance.h): RMS roughness sigma (m),
  // mean absolute asperity slope m, microhardness of its surface layer (Pa; 0: not given).
  // 0, 0, 0 is a smooth surface.
  double roughness_m = 0.0;
  double asperity_slope = 0.0;
  double microhardness_Pa = 0.0;
};

// Hertz contact radius a = (3 F R* / (4 E*))^(1/3), m; 1/R* = 1/R1 + 1/R2,
// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2. A non-positive force gives a = 0.
// flattening f >= 0: a loaded contact's spot is at least f R* (a = max(a_Hertz, f R*)), the
// flattened contact of rough or plastically deformed beads that the Zehner-Schlunder-Bauer
// correlation's flattening term stands for (docs/heat-modes.md "Flattened contacts").
double hertz_contact_radius_m(const ContactBody& b1, const ContactBody& b2, double normal_force_N,
                              double flattening = 0.0);

// H = 2 k a with k the harmonic mean 2 k1 k2 / (k1 + k2), W/K.
double hertz_conductance_W_per_K(const ContactBody& b1, const ContactBody& b2,
                                 double normal_force_N, double flattening = 0.0);

// hertz: H = 2 k a (above); constant: one H for every contact; bahrami: rough surfaces, the Hertz
// spot in series with its micro-contacts and micro-gap (RoughContactConductance.h). The scene's
// thermal.conductance, parsed once where the scene is read.
enum class ConductanceLawKind { Hertz, Constant, Bahrami };
// The names, in the enum's order: the one list (the scene schema's choices take it).
inline constexpr std::array<std::string_view, 3> kConductanceLawNames{"hertz", "constant", "bahrami"};

// An unknown name throws std::invalid_argument listing the valid names.
inline ConductanceLawKind conductance_law_from_name(std::string_view name) {
  return parse_kind<ConductanceLawKind>(name, kConductanceLawNames, "conductance law");
}
constexpr std::string_view name_of(ConductanceLawKind law) { return kind_name(law, kConductanceLawNames); }
// The law reads the contact's normal force (so a run needs forces: mechanics or imported ones).
bool conductance_law_uses_force(ConductanceLawKind law);

}  // namespace tmdem::thermal
