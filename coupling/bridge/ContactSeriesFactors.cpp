#include "coupling/bridge/ContactSeriesFactors.h"

#include <cstdint>
#include <unordered_map>

#include "mechanics/model/PairIndex.h"

namespace tmdem::coupling {

bool contact_conductances_in_series(const ContactList& contacts,
                                    const thermal::ThermalNetwork& network,
                                    std::vector<double>& out) {
  if (network.edge_series_factor.empty() && network.wall_series_factor.empty()) return false;
  auto key = [](std::int64_t a, std::int64_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | std::uint64_t(b);
  };
  std::unordered_map<std::uint64_t, double> pair_factor;
  for (std::size_t e = 0; e < network.edge_count(); ++e)
    pair_factor.emplace(key(network.edge_a[e], network.edge_b[e]), network.edge_factor(e));
  // Wall edges of each node, in network order; consumed in contact order.
  std::unordered_map<std::int64_t, std::vector<std::size_t>> wall_edges;
  for (std::size_t w = 0; w < network.wall_edge_count(); ++w)
    wall_edges[network.wall_node[w]].push_back(w);
  out.assign(contacts.conductance_W_per_K.begin(), contacts.conductance_W_per_K.end());
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const std::int64_t i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    if (!mechanics::is_wall(j)) {
      if (const auto it = pair_factor.find(key(i, j)); it != pair_factor.end()) out[c] *= it->second;
      continue;
    }
    // The network keeps no wall index per edge: the particle's first unused wall edge with this
    // contact's conductance (copied from it when the network was built, so equal to the bit;
    // open edges of a dynamic run's sticky pattern have 0 and are passed over).
    const auto it = wall_edges.find(i);
    if (it == wall_edges.end()) continue;
    auto& candidates = it->second;
    for (auto k = candidates.begin(); k != candidates.end(); ++k) {
      if (network.wall_conductance_W_per_K[*k] != contacts.conductance_W_per_K[c]) continue;
      out[c] *= network.wall_factor(*k);
      candidates.erase(k);
      break;
    }
  }
  return true;
}

}  // namespace tmdem::coupling
