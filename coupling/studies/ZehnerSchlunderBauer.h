#pragma once
// The Zehner-Schlunder-Bauer correlation for the effective conductivity of a packed bed of
// spheres in a stagnant gas, as the VDI Heat Atlas (2nd ed., 2010, section D6.3, Tsotsas) writes
// it: the bed is a parallel of a gas path (share 1 - sqrt(1 - psi)) and a unit-cell path through
// flattened solid contacts (share phi of sqrt(1 - psi)) and through particle-gas-particle
// columns whose shape follows B = C_f ((1 - psi) / psi)^(10/9), with the gas conductivity near
// the particles lowered by the Smoluchowski temperature jump (k_G = 1 / (1 + l / d)) and
// radiation between the surfaces as a parallel conductivity k_rad:
//
//   k_eff / k_f = (1 - sqrt(1-psi)) psi [(psi - 1 + 1/k_G)^-1 + k_rad]
//               + sqrt(1-psi) [phi k_p + (1 - phi) k_c],
//   N   = (1/k_G) (1 + (k_rad - B k_G) / k_p) - B (1/k_G - 1) (1 + k_rad / k_p),
//   k_c = (2/N) [ B (k_p + k_rad - 1) / (N^2 k_G k_p) ln((k_p + k_rad) / (B (k_G + (1 - k_G)(k_p + k_rad))))
//                 + (B + 1) / (2B) (k_rad / k_G - B (1 + (1 - k_G) / k_G k_rad)) - (B - 1) / (N k_G) ],
//
// k_p = k_s / k_f, k_rad = 4 sigma / (2/eps - 1) T^3 d / k_f. tmdem uses it as the reference of
// its bulk-bed validation (docs/validation.md) and `study conductivity` prints it beside k_eff.

namespace tmdem::coupling {

struct ZehnerSchlunderBauerInput {
  double porosity = 0.4;           // psi, in (0, 1)
  double k_solid_W_per_mK = 1.0;   // k_s
  double k_fluid_W_per_mK = 0.0262;  // k_f, of the gas at continuum pressure
  double diameter_m = 1e-3;        // d
  double shape_factor = 1.25;      // C_f: 1.25 for spheres
  double flattening = 0.0;         // phi: share of the solid path through flattened contacts
                                   // (VDI: 0.0077 for spheres of a typical bed)
  double jump_length_m = 0.0;      // l = 2 (2 - gamma) / gamma * mean free path (0: continuum)
  double emissivity = 0.0;         // eps of the surfaces (0: no radiation)
  double temperature_K = 0.0;      // T of the radiation term
};

struct ZehnerSchlunderBauerResult {
  double k_eff_W_per_mK = 0.0;
  double k_G = 1.0;    // Smoluchowski factor of the gas near the particles
  double k_rad = 0.0;  // radiation, in units of k_f
  double k_c = 0.0;    // the unit cell's particle-gas core, in units of k_f
};

// Throws std::invalid_argument for inputs outside the correlation's domain (porosity outside
// (0, 1), non-positive conductivities or diameter, emissivity outside [0, 1]).
ZehnerSchlunderBauerResult zehner_schlunder_bauer(const ZehnerSchlunderBauerInput& in);

}  // namespace tmdem::coupling
