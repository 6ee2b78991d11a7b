#pragma once
// Uniform cell grid over the bounding box of a set of points, built by counting sort.
// With cells at least as large as the largest interaction distance, every pair that can
// interact lies in the same or in adjacent cells, so listing candidates costs O(N) instead
// of O(N^2) (the "partitionnement" of MULTICOR, [FOR 03]).
//
// Rebuilding reuses the arrays' capacity: no allocation once the particle count is stable.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tmdem::mechanics {

class CellGrid {
 public:
  // Sorts the points into cells of edge >= min_cell_size_m. The edge is enlarged when the
  // bounding box would otherwise need more than a few cells per point (a particle far away
  // from the others must not blow up memory). Throws std::invalid_argument on non-finite
  // input or a non-positive cell size.
  void build(const std::vector<Eigen::Vector3d>& points, double min_cell_size_m);

  // Calls visit(a, b) exactly once for every unordered pair of distinct points that lie in
  // the same or in adjacent cells (a and b in no particular order).
  template <class Visit>
  void for_each_candidate_pair(Visit&& visit) const;

  double cell_size() const { return cell_size_; }
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

 private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_size_ = 0.0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint32_t> cell_of_;     // cell of each point
  std::vector<std::uint32_t> cell_start_;  // points of cell c are sorted_[start[c], start[c+1])
  std::vector<std::uint32_t> sorted_;      // point ids ordered by cell
};

template <class Visit>
void CellGrid::for_each_candidate_pair(Visit&& visit) const {
  // Half of the 26 neighbours: each adjacent pair of cells is visited from one side only.
  static constexpr int kOffsets[13][3] = {{1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},
                                          {-1, -1, 1}, {0, -1, 1}, {1, -1, 1}, {-1, 0, 1},
                                          {0, 0, 1},  {1, 0, 1},  {-1, 1, 1}, {0, 1, 1},
                                          {1, 1, 1}};
  for (int cz = 0; cz < nz_; ++cz) {
    for (int cy = 0; cy < ny_; ++cy) {
      for (int cx = 0; cx < nx_; ++cx) {
        const std::size_t c = (static_cast<std::size_t>(cz) * ny_ + cy) * nx_ + cx;
        const std::uint32_t begin = cell_start_[c], end = cell_start_[c + 1];
        if (begin == end) continue;
        for (std::uint32_t a = begin; a < end; ++a) {
          for (std::uint32_t b = a + 1; b < end; ++b) visit(sorted_[a], sorted_[b]);
        }
        for (const auto& o : kOffsets) {
          const int x = cx + o[0], y = cy + o[1], z = cz + o[2];
          if (x < 0 || x >= nx_ || y < 0 || y >= ny_ || z < 0 || z >= nz_) continue;
          const std::size_t d = (static_cast<std::size_t>(z) * ny_ + y) * nx_ + x;
          const std::uint32_t dbegin = cell_start_[d], dend = cell_start_[d + 1];
          for (std::uint32_t a = begin; a < end; ++a) {
            for (std::uint32_t b = dbegin; b < dend; ++b) visit(sorted_[a], sorted_[b]);
          }
        }
      }
    }
  }
}

}  // namespace tmdem::mechanics
