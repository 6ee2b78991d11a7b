#include "thermal/system/JacobianPattern.h"

#include <algorithm>

namespace tmdem::thermal {

void JacobianPattern::build(const ThermalNetwork& net) {
  const std::size_t n = net.node_count();
  const std::size_t m = net.edge_count();
  // Count neighbours per column (duplicates included), then fill and sort each column.
  std::vector<std::int64_t> start(n + 1, 0);
  for (std::size_t e = 0; e < m; ++e) {
    ++start[net.edge_a[e] + 1];
    ++start[net.edge_b[e] + 1];
  }
  for (std::size_t j = 0; j < n; ++j) start[j + 1] += start[j] + 1;  // +1: the diagonal
  std::vector<std::int64_t> rows(start[n]);
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (std::size_t j = 0; j < n; ++j) rows[fill[j]++] = std::int64_t(j);
  for (std::size_t e = 0; e < m; ++e) {
    rows[fill[net.edge_b[e]]++] = net.edge_a[e];  // entry (a, b) lives in column b
    rows[fill[net.edge_a[e]]++] = net.edge_b[e];
  }
  // Sort and de-duplicate each column into the final arrays.
  column_start.assign(n + 1, 0);
  row_index.clear();
  row_index.reserve(rows.size());
  for (std::size_t j = 0; j < n; ++j) {
    auto first = rows.begin() + start[j], last = rows.begin() + start[j + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    row_index.insert(row_index.end(), first, last);
    column_start[j + 1] = std::int64_t(row_index.size());
  }
  auto slot_of = [&](std::int64_t row, std::int64_t col) {
    const auto b = row_index.begin() + column_start[col];
    const auto e = row_index.begin() + column_start[col + 1];
    return std::int64_t(std::lower_bound(b, e, row) - row_index.begin());
  };
  diagonal_slot.resize(n);
  for (std::size_t j = 0; j < n; ++j) diagonal_slot[j] = slot_of(std::int64_t(j), std::int64_t(j));
  slot_ab.resize(m);
  slot_ba.resize(m);
  for (std::size_t e = 0; e < m; ++e) {
    slot_ab[e] = slot_of(net.edge_a[e], net.edge_b[e]);
    slot_ba[e] = slot_of(net.edge_b[e], net.edge_a[e]);
  }
  node_edge_start.assign(n + 1, 0);
  for (std::size_t e = 0; e < m; ++e) {
    ++node_edge_start[std::size_t(net.edge_a[e]) + 1];
    ++node_edge_start[std::size_t(net.edge_b[e]) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) node_edge_start[i + 1] += node_edge_start[i];
  node_edge.resize(std::size_t(node_edge_start[n]));
  std::vector<std::int64_t> next(node_edge_start.begin(), node_edge_start.end() - 1);
  for (std::size_t e = 0; e < m; ++e) {  // ascending e: each node's list comes out sorted
    node_edge[std::size_t(next[std::size_t(net.edge_a[e])]++)] = std::int32_t(e);
    node_edge[std::size_t(next[std::size_t(net.edge_b[e])]++)] = std::int32_t(e);
  }
}

}  // namespace tmdem::thermal
