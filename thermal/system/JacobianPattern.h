#pragma once
// Compressed-sparse-column pattern of the conductance Laplacian (plus diagonal mode terms):
// column j holds row j and the rows of j's neighbours. Built once per contact-graph shape; while
// the shape holds, only values are rewritten, through the slot maps below.
#include <cstdint>
#include <vector>

#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

struct JacobianPattern {
  std::vector<std::int64_t> column_start;  // n + 1
  std::vector<std::int64_t> row_index;     // nnz, sorted within each column
  std::vector<std::int64_t> diagonal_slot; // n: slot of (i, i)
  std::vector<std::int64_t> slot_ab;       // per edge: slot of (row a, column b)
  std::vector<std::int64_t> slot_ba;       // per edge: slot of (row b, column a)
  // The edges touching each node, in increasing edge order: node i's are
  // node_edge[node_edge_start[i] .. node_edge_start[i + 1]). A loop over nodes that adds each
  // node's edge terms in this order adds them in the order a loop over edges does, so it gives
  // the same bits on any number of threads (ThermalSystem::jacobian_times).
  std::vector<std::int64_t> node_edge_start;  // n + 1
  std::vector<std::int32_t> node_edge;        // 2 per edge

  // Duplicate edges (the same pair twice) share one slot; assembly then adds them up.
  void build(const ThermalNetwork& network);
  std::size_t nonzeros() const { return row_index.size(); }
  std::size_t size() const { return diagonal_slot.size(); }
};

}  // namespace tmdem::thermal
