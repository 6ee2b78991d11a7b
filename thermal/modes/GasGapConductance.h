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

// Vargas & McCarthy (2002) stagnant-fluid conductance of a touching pair, in the closed form
// used by Kratos ThermalDEM (IndirectConductionVargas): with the mean radius R = (R_a + R_b)/2
// (a plane: R = R_a) and contact radius a,
//   H = 2 pi k_f (R - a) (1 - a^2 / (2 R^2)) / (1 - pi/4).
// Defined for touching pairs only; the caller passes touching pairs.
double vargas_mccarthy_conductance_W_per_K(const GasGap& gap, double fluid_conductivity_W_per_mK);

}  // namespace tmdem::thermal
