#pragma once
// The heat flow of a mode that is affine in T and fixed in time, q = K T + f, as plain entries.
// The accuracy study's exact reference (coupling/studies/ExactThermalReference.h) assembles its
// operator from these, mode by mode, so it names no mode itself. Each mode writes its entries
// from its physics, apart from add_heat_flow and add_jacobian: the reference does not reuse the
// code it judges.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tmdem::thermal {

struct AffineHeatFlow {
  // Entries of K = d q / d T, W/K; a repeated (row, column) adds up, in the order written.
  std::vector<std::int64_t> row, column;
  std::vector<double> value_W_per_K;
  std::vector<double> constant_W;  // f, W, one per node (sized by whoever asks the modes)

  explicit AffineHeatFlow(std::size_t node_count = 0) : constant_W(node_count, 0.0) {}
  void add(std::int64_t r, std::int64_t c, double value) {
    row.push_back(r);
    column.push_back(c);
    value_W_per_K.push_back(value);
  }
};

}  // namespace tmdem::thermal
