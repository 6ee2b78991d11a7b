#pragma once
// The contacts of one moment, in the result-file layout (contract section 3): the mechanics'
// contacts become the thermal network's edges through this list.
#include <array>
#include <cstdint>
#include <vector>

namespace tmdem::coupling {

struct ContactList {
  std::vector<std::int64_t> pair;                 // 2 per contact: i, j (j may be a wall: mechanics/model/PairIndex.h)
  std::vector<double> normal_force_N;             // per contact
  std::vector<double> conductance_W_per_K;        // per contact, filled by the network builder
  std::vector<double> tangential_force_N;         // 3 per contact: xyz, the tangential part of
                                                  // the reaction on i (0 without mechanics)
  std::vector<double> dissipated_power_W;         // per contact: mechanical power the contact
                                                  // dissipated over the step (0 when frozen)

  std::size_t size() const { return normal_force_N.size(); }
  void clear() {
    pair.clear();
    normal_force_N.clear();
    conductance_W_per_K.clear();
    tangential_force_N.clear();
    dissipated_power_W.clear();
  }
  void add(std::int64_t i, std::int64_t j, double force_N,
           const std::array<double, 3>& tangential_N = {0.0, 0.0, 0.0},
           double dissipated_W = 0.0) {
    pair.push_back(i);
    pair.push_back(j);
    normal_force_N.push_back(force_N);
    conductance_W_per_K.push_back(0.0);
    tangential_force_N.insert(tangential_force_N.end(), tangential_N.begin(), tangential_N.end());
    dissipated_power_W.push_back(dissipated_W);
  }
};

}  // namespace tmdem::coupling
