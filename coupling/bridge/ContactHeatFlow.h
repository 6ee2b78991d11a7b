#pragma once
// The heat flow through each contact of a ContactList at given temperatures (result file
// /contacts/heat_flow): Q = H (T_i - T_j) in W, positive from i to j; for a wall contact
// Q = H (T_i - T_wall), 0 for an adiabatic wall (its conductance is 0).
#include <span>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// out gets one value per contact (resized; no allocation once large enough).
void contact_heat_flow_W(const ContactList& contacts, std::span<const double> temperature_K,
                         const Scene& scene, std::vector<double>& out);

}  // namespace tmdem::coupling
