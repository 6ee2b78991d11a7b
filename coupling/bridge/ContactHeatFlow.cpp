#include "coupling/bridge/ContactHeatFlow.h"

namespace tmdem::coupling {

void contact_heat_flow_W(const ContactList& contacts, std::span<const double> temperature_K,
                         const Scene& scene, std::vector<double>& out) {
  out.resize(contacts.size());
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const double H = contacts.conductance_W_per_K[c];
    const auto i = std::size_t(contacts.pair[2 * c]);
    const std::int64_t j = contacts.pair[2 * c + 1];
    double T_other = temperature_K[i];  // adiabatic wall: no flow whatever H says
    if (j >= 0) {
      T_other = temperature_K[std::size_t(j)];
    } else if (const auto& T_wall = scene.walls[std::size_t(-1 - j)].temperature_K; T_wall) {
      T_other = *T_wall;
    }
    out[c] = H * (temperature_K[i] - T_other);
  }
}

}  // namespace tmdem::coupling
