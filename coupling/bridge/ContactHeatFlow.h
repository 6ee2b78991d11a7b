#pragma once
// The heat flow through each contact of a ContactList at time t (result file
// /contacts/heat_flow), in W, positive from i to j:
//   particle-particle  Q = H (T_i - T_j)
//   isothermal wall    Q = H (T_i - T_wall(t))   (a tabled wall at its value at t)
//   heat-flux wall     Q = -P_w H / sum_k H_kw   (its power shared by conductance, as the
//                                                 wall_flux mode does; negative: into i)
//   adiabatic wall     Q = 0
#include <span>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// out gets one value per contact, H taken from conductance_W_per_K (one per contact: the
// list's own, or those in series with the particles' shells). Called once per frame (two small
// per-wall arrays).
void contact_heat_flow_W(const ContactList& contacts, std::span<const double> conductance_W_per_K,
                         std::span<const double> temperature_K, double time_s, const Scene& scene,
                         std::vector<double>& out);

}  // namespace tmdem::coupling
