#pragma once
// The particle's own thermal resistance (thermal.particle_resistance = "isothermal_core";
// docs/heat-modes.md "The particle's own resistance").
//
// A particle is an isothermal core of radius c r at the node's temperature inside a solid shell
// c r < rho < r of conductivity k. The heat of one pair path crosses the shell radially inside
// the cone that the partner subtends from the particle's centre: the partner of radius r_b at
// centre distance d (d = r + r_b + gap) is seen under the half-angle theta, sin theta = r_b / d,
// a solid angle Omega = 2 pi (1 - cos theta). An isothermal wall is replaced by the particle's
// mirror image (the wall is the symmetry plane of the mirrored pair): r_b = r, d = 2 (r + gap).
// Radial conduction in a cone between the radii c r and r has the resistance
//   R = (1/(c r) - 1/r) / (k Omega) = S / Omega,  S = (1/(c r) - 1/r) / k  (K sr/W, per node),
// and the pair's conductance becomes H' = 1 / (1/H_pair + R_a + R_b) (a wall: R_a only), with
// H_pair the sum of the pair conductances of every mode on that pair (contact and gas share
// the solid near the contact). Each mode scales its own H by H'/H_pair, so the modes' flows add
// up to H' (T_b - T_a).
#include <span>

#include "thermal/modes/HeatTransferMode.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

// S = (1/(c r) - 1/r) / k, K sr/W. core_fraction c in (0, 1), radius r > 0, conductivity k > 0.
double shell_resistance_K_sr_per_W(double radius_m, double conductivity_W_per_mK,
                                   double core_fraction);

// Solid angle (sr) of the cone that a sphere of radius partner_radius_m, its centre at
// centre_distance_m, subtends from a point: 2 pi (1 - cos theta), sin theta = min(1, r_b / d).
double partner_solid_angle_sr(double partner_radius_m, double centre_distance_m);

// Series resistance of node a's shell on particle edge e (K/W), and on wall edge w.
double edge_shell_resistance_K_per_W(const ThermalNetwork& net, std::size_t e, bool side_a);
double wall_shell_resistance_K_per_W(const ThermalNetwork& net, std::size_t w);

// Writes net.edge_series_factor and net.wall_series_factor from the pair conductances of
// `modes` (HeatTransferMode::add_pair_conductance, after their update_geometry); clears them
// when net.shell_resistance_K_sr_per_W is empty (no particle resistance: today's bits).
void update_series_factors(ThermalNetwork& net, std::span<const HeatTransferMode* const> modes);

}  // namespace tmdem::thermal
