#pragma once
// Conductance of the stagnant gas (or liquid) between two spheres, or between a sphere and a
// plane wall, W/K: the models of effects.gas_conduction (thermal/modes/GasConductionMode.cpp; docs/heat-modes.md
// "Gas in the gaps" gives equations, sources and validity).
#include <cstddef>
#include <limits>

namespace tmdem::thermal {

struct GasGap {
  double radius_a_m = 0.0;
  double radius_b_m = std::numeric_limits<double>::infinity();  // infinity: a plane wall
  double gap_m = 0.0;             // surface gap; < 0 for an overlap
  double contact_radius_m = 0.0;  // radius of the solid contact disc (0: point or no contact)
  // The particles' own resistance resolved per ray (thermal.particle_resistance =
  // "isothermal_core_rays"): each sphere's shell as the gas thickness that conducts like it on
  // the ray through the axis, k_f S R^2 (S in K sr/W, ParticleResistance.h); on the ray at r
  // from the axis it is that times cos theta = sqrt(1 - (r/R)^2). 0: no shell (a wall has none).
  double shell_gap_a_m = 0.0;
  double shell_gap_b_m = 0.0;
};

// Surrounding fluid layer (Rong & Horio 1999; Musser 2011; Morris et al. 2016): heat flows
// parallel to the line of centres through the gas lens inside a fluid layer of thickness
// layer_fraction * r_min around the larger body,
//   H = k_f * integral_{r_in}^{r_out} 2 pi r dr / max(L_min, S(r)),
// S(r) = d - sqrt(R_a^2 - r^2) - sqrt(R_b^2 - r^2) the gas thickness at distance r from the
// axis (plane: h - sqrt(R^2 - r^2)), r_in the contact radius, r_out where the layer meets the
// other body (at most r_min). Zero once the gap exceeds the layer. Evaluated as the exact
// constant-S part plus adaptive Gauss-Kronrod (G7K15) in r = r_min sin(theta), relative
// accuracy about 1e-12.
// With shells (GasGap::shell_gap_a_m, shell_gap_b_m) each ray also crosses both solid shells in
// series: 1 / (max(L_min, S(r)) + l + t_a cos theta_a(r) + t_b cos theta_b(r)).
// A rarefied gas (Smoluchowski): the gas meets each surface with a temperature jump, as if the
// gap were wider by the jump length l (both surfaces together), so 1 / max(L_min, S(r)) becomes
// 1 / (max(L_min, S(r)) + l); l = 0: continuum (gas_jump_length_m, below).
// max_disk_radius_m clips the integration disk, r_out -> min(r_out, max_disk_radius_m): the
// pair's share of the gas when neighbouring layers overlap (equal_share_disk_radius_m, below);
// infinity: the whole layer.
double surrounding_layer_conductance_W_per_K(
    const GasGap& gap, double fluid_conductivity_W_per_mK, double layer_fraction, double min_gap_m,
    double jump_length_m = 0.0,
    double max_disk_radius_m = std::numeric_limits<double>::infinity());

// True when the pair lies inside the surrounding layer (gap < layer_fraction * r_min), i.e. its
// layer conducts at all: the neighbours that share a particle's gas.
bool surrounding_layer_reaches(const GasGap& gap, double layer_fraction);

// Equal share of a particle's surroundings among its z neighbours within the layer
// (fluid.layer_share = "equal_solid_angle", docs/heat-modes.md "Gas in the gaps"): the cone of
// solid angle 4 pi / z around a pair's axis, 2 pi (1 - cos t) = 4 pi / z, meets the particle's
// surface at the distance R sin t = 2 R sqrt(z - 1) / z from the axis. That distance (z >= 2; R
// itself at z = 2), infinity for z <= 1 (nothing to share). m.
double equal_share_disk_radius_m(double radius_m, std::size_t neighbours);

// The Smoluchowski jump length of both surfaces of a gap, as the VDI Heat Atlas writes it for
// the Zehner-Schlunder-Bauer model: l = 2 (2 - gamma) / gamma * Lambda, with the accommodation
// coefficient gamma in (0, 1] and the mean free path Lambda = Lambda_ref * p_ref / p (kinetic
// theory at a fixed temperature; Lambda_ref at p_ref = 101325 Pa). m; 0 for p = 0 (continuum).
double gas_jump_length_m(double pressure_Pa, double mean_free_path_at_1atm_m, double accommodation);

// Bahrami's gas parameter M (m): the temperature-jump distance of a gap's two surfaces in a
// rarefied gas (Bahrami, Yovanovich & Culham 2006, after Yovanovich's gap model),
//   M = ((2 - alpha_1)/alpha_1 + (2 - alpha_2)/alpha_2) (2 gamma / (1 + gamma)) Lambda / Pr,
// alpha_i the thermal accommodation coefficients of the surfaces, gamma = c_p / c_v of the gas,
// Pr its Prandtl number, Lambda = Lambda_ref * 101325 Pa / p its mean free path (Lambda_ref at
// 101325 Pa); 0 for p = 0 (continuum).
double gas_parameter_m(double pressure_Pa, double mean_free_path_at_1atm_m, double accommodation_1,
                       double accommodation_2, double heat_capacity_ratio, double prandtl);

// The macro-gap of Bahrami, Yovanovich & Culham (2006) (fluid.model = "bahrami"): the gas between
// touching spheres, or a sphere and a plane wall, outside their contact disc of radius a, out to
// the smaller radius r_min (the paper's simple-cubic cell, whose flux tube is the sphere's own
// radius: its "B = 0"), in series with the temperature jump M of the two surfaces:
//   H = k_f int_a^r_min 2 pi r dr / (delta(r) + M),   delta(r) = s(r) - s(a),
// s(r) = (R_a - sqrt(R_a^2 - r^2)) + (R_b - sqrt(R_b^2 - r^2)) (a plane adds 0): the surfaces
// meet at the rim of the disc and open with the spheres' curvature (the paper's profile; the
// overlap or gap of the rigid packing is not used). Equal spheres give the paper's closed form
// (pi k_f / 2) [S ln(S / (S - A)) - A], A = 2 sqrt(R^2 - a^2), S = A + M; a sphere on a plane
// 2 pi k_f [S ln(S / (S - u)) - u], u = sqrt(R^2 - a^2), S = u + M. Evaluated for every pair by
// adaptive Gauss-Kronrod (G7K15) in r = r_min sin(theta), relative accuracy about 1e-12.
// M > 0 (the conductance diverges as M -> 0 at the rim). Defined for touching pairs only; the
// caller passes touching pairs.
double bahrami_macrogap_conductance_W_per_K(const GasGap& gap, double fluid_conductivity_W_per_mK,
                                            double gas_parameter_m);

// Vargas & McCarthy (2002) stagnant-fluid conductance of a touching pair, in the closed form
// used by Kratos ThermalDEM (IndirectConductionVargas): with the mean radius R = (R_a + R_b)/2
// (a plane: R = R_a) and contact radius a,
//   H = 2 pi k_f (R - a) (1 - a^2 / (2 R^2)) / (1 - pi/4).
// Defined for touching pairs only; the caller passes touching pairs.
double vargas_mccarthy_conductance_W_per_K(const GasGap& gap, double fluid_conductivity_W_per_mK);

}  // namespace tmdem::thermal
