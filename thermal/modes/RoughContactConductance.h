#pragma once
// The conductance of a contact between rough spheres (or a rough sphere and a wall), from measured
// surface properties: thermal.conductance = "bahrami" (docs/heat-modes.md "Rough contacts").
// The network of Bahrami, Yovanovich & Culham (2006) as Beaulieu (2020) applied it to a bed of
// steel spheres in air: the Hertz spot of radius a (the macro-contact) constricts the heat into
// each body, and inside the spot the heat crosses the interface through the asperities that
// touch (micro-contacts) and, beside them, through the gas between the asperities (micro-gap):
//
//   H = 1 / (R_L + 1 / (1/R_s + 1/R_g))
//
//   R_L = 1 / (2 k a)         constriction into two half-spaces (Hertz: H = 2 k a), k = 2 k1 k2 / (k1 + k2)
//   R_s = (1 + n/2) / (1.25 pi k a^2) (sigma/m) (H_mic/P0)^n,   n = 0.95
//                             the conforming rough-surface conductance of Cooper, Mikic &
//                             Yovanovich, h = 1.25 k (m/sigma) (P/H_mic)^0.95 (Yovanovich 1982),
//                             taken at the local Hertz pressure P(r) = P0 sqrt(1 - r^2/a^2) and
//                             summed over the spot: int_0^a (1 - r^2/a^2)^(n/2) 2 pi r dr = pi a^2 / (1 + n/2)
//   R_g = 2 sqrt(2) sigma a2 / (pi k_g a^2 ln(1 + a2 / (a1 + M / (2 sqrt(2) sigma))))
//                             the gas between conforming rough surfaces (Bahrami et al. 2004, 2006),
//                             a1 = erfc^-1(2 P0 / H_mic), a2 = erfc^-1(0.03 P0 / H_mic) - a1,
//                             M the gas parameter (GasGapConductance.h, gas_parameter_m)
//
// with P0 = 3 F / (2 pi a^2) the peak Hertz pressure, sigma = sqrt(sigma1^2 + sigma2^2) and
// m = sqrt(m1^2 + m2^2) the surfaces' combined roughness and slope, H_mic the microhardness of the
// softer surface (the asperities that yield are the softer ones'). Smooth surfaces (sigma = 0)
// give R_s = 0, so H = 2 k a: the Hertz law. The gas between the spheres outside the spot (the
// macro-gap) is the gas mode's (GasGapConductance.h, bahrami_macrogap_conductance_W_per_K).
//
// Sources: M. Bahrami, M. M. Yovanovich, J. R. Culham, "Effective thermal conductivity of rough
// spherical packed beds", Int. J. Heat Mass Transfer 49 (2006) 3691-3701; M. Bahrami, J. R.
// Culham, M. M. Yovanovich, "Thermal joint resistances of conforming rough surfaces with
// gas-filled gaps", J. Thermophys. Heat Transfer 18 (2004) 318-325; M. M. Yovanovich, "Thermal
// contact correlations", AIAA Progress in Astronautics and Aeronautics 83 (1982) 83-95;
// C. Beaulieu, PhD thesis, Polytechnique Montreal (2020), as documented by Lethe's DEM heat
// transfer (chaos-polymtl/lethe, doc/source/theory/multiphase/dem/dem.rst).
#include "thermal/modes/ConductanceLaw.h"

namespace tmdem::thermal {

// The gas in a contact's micro-gap: its conductivity (0: vacuum, no micro-gap) and Bahrami's gas
// parameter M (m), the temperature-jump distance of the gap's two surfaces.
struct ContactGas {
  double conductivity_W_per_mK = 0.0;
  double gas_parameter_m = 0.0;
};

// The three resistances of a loaded contact, K/W; infinity where a path is absent (no gas, or a
// spot pressed beyond the micro-gap model's range), 0 for micro-contacts of smooth surfaces.
struct RoughContactResistances {
  double macrocontact_K_per_W = 0.0;  // R_L
  double microcontacts_K_per_W = 0.0; // R_s
  double microgap_K_per_W = 0.0;      // R_g
  // 1 / (R_L + 1 / (1/R_s + 1/R_g)), W/K.
  double conductance_W_per_K() const;
};

// The resistances at normal force F > 0 (N). Throws std::invalid_argument for rough surfaces
// (sigma > 0) without a slope m > 0 or a microhardness (the scene refuses them first).
RoughContactResistances rough_contact_resistances(const ContactBody& b1, const ContactBody& b2,
                                                  double normal_force_N, const ContactGas& gas);

// H of the contact, W/K; 0 for a non-positive force (no contact).
double rough_contact_conductance_W_per_K(const ContactBody& b1, const ContactBody& b2,
                                         double normal_force_N, const ContactGas& gas);

// Peak Hertz pressure P0 = 3 F / (2 pi a^2) (= 2 E* a / (pi R*)), Pa; 0 without force.
double hertz_peak_pressure_Pa(const ContactBody& b1, const ContactBody& b2, double normal_force_N);

// x with erfc(x) = y, for y in (0, 2) (safeguarded Newton, to a few ulps).
double inverse_erfc(double y);

}  // namespace tmdem::thermal
