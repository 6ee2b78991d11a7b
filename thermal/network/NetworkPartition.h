#pragma once
// Which process owns which particle when the heating runs over MPI (docs/scale-out.md): the
// nodes in a "partition order" whose contiguous blocks are the processes' shares. A node's
// position in that order is its global row: hypre's distributed matrix and SUNDIALS' parallel
// vector need each process's unknowns to be one contiguous range of rows. No MPI here: every
// process computes the same partition from the same positions.
#include <cstdint>
#include <span>
#include <vector>

namespace tmdem::thermal {

class NetworkPartition {
 public:
  // Slabs across the longest extent of the bed: the nodes sorted by their centre's coordinate
  // along the axis of the largest bounding-box extent (ties by node id, so every process gets
  // the same order), cut into `ranks` blocks of equal count (the first n % ranks one larger).
  // Slabs keep each process's interface to two planes; for the two to a few processes of one
  // machine that is as good as recursive bisection. xyz_m: 3 per node.
  static NetworkPartition slabs(std::span<const double> xyz_m, int ranks);

  int ranks() const { return int(first_row_.size()) - 1; }
  // The axis the slabs cut across (0, 1, 2: x, y, z).
  int axis() const { return axis_; }
  std::size_t node_count() const { return order_.size(); }
  std::int32_t node_at_row(std::int32_t row) const { return order_[std::size_t(row)]; }
  std::int32_t row_of(std::int32_t node) const { return row_[std::size_t(node)]; }
  int owner(std::int32_t node) const { return owner_[std::size_t(node)]; }
  // Rows [first_row(r), first_row(r + 1)) belong to rank r.
  std::int32_t first_row(int rank) const { return first_row_[std::size_t(rank)]; }
  std::int32_t owned_count(int rank) const { return first_row(rank + 1) - first_row(rank); }

 private:
  std::vector<std::int32_t> order_;      // row -> node
  std::vector<std::int32_t> row_;        // node -> row
  std::vector<int> owner_;               // node -> rank
  std::vector<std::int32_t> first_row_;  // rank -> first row; one more entry: the node count
  int axis_ = 0;
};

}  // namespace tmdem::thermal
