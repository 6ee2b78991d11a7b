#pragma once
// The particle's own resistance (thermal.particle_resistance, docs/heat-modes.md) puts each
// pair's conductances in series with the two particles' shells: the thermal network holds one
// factor H'/H per edge (ThermalNetwork::edge_series_factor, wall_series_factor). This maps them
// back onto the contacts of a ContactList, so that the result file's /contacts/conductance and
// /contacts/heat_flow are those of the path the heat takes (f H and f H (T_i - T_j)).
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::coupling {

// Each contact's conductance in series with its particles' shells, f H, into `out` (one per
// contact); false, `out` untouched, when the network has no series factors (the key off: the
// list's own conductances stand). Particle pairs are matched by their two nodes; a contact with
// an isothermal wall by its particle and its contact conductance (two walls touching one particle
// with the same conductance, a box corner, are told apart by their order only); heat-flux and
// adiabatic walls keep H (no shell: a flux wall imposes its power).
bool contact_conductances_in_series(const ContactList& contacts,
                                    const thermal::ThermalNetwork& network,
                                    std::vector<double>& out);

}  // namespace tmdem::coupling
