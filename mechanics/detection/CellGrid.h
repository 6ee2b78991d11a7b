#pragma once
// Uniform cell grid over the bounding box of a set of points, built by counting sort.
// With cells at least as large as the largest interaction distance, every pair that can
// interact lies in the same or in adjacent cells, so listing candidates costs O(N) instead
// of O(N^2) (the "partitionnement" of MULTICOR, [FOR 03]).
//
// Rebuilding reuses the arrays' capacity: no allocation once the particle count is stable.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/model/ParallelFrom.h"
#include "mechanics/model/PeriodicBox.h"

namespace tmdem::mechanics {

class CellGrid {
 public:
  // Sorts the points into cells of edge >= min_cell_size_m. The edge is enlarged when the
  // bounding box would otherwise need more than a few cells per point (a particle far away
  // from the others must not blow up memory). Throws std::invalid_argument on non-finite
  // input or a non-positive cell size.
  //
  // Along a periodic axis of `box` the grid spans the period [low, high) in whole cells (at
  // least min_cell_size_m each) and the first and last cells are neighbours; the points must
  // lie in the period (wrapped). An axis of fewer than 3 cells visits all of them as neighbours
  // (each once), which stays correct for any period.
  void build(const std::vector<Eigen::Vector3d>& points, double min_cell_size_m,
             const PeriodicBox& box = {});

  // Calls visit(a, b) exactly once for every unordered pair of distinct points that lie in
  // the same or in adjacent cells (a and b in no particular order).
  template <class Visit>
  void for_each_candidate_pair(Visit&& visit) const;

  // Calls visit(b) for every point b != a in the cell of point a or in one of its 26
  // neighbours (cells in increasing index order, points in increasing id order inside a
  // cell). Read-only: any number of threads may call it at once (parallel detection).
  template <class Visit>
  void for_each_neighbour(std::uint32_t a, Visit&& visit) const;

  double cell_size() const { return cell_size_; }  // m, the smallest edge
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

  // Point count from which build() uses OpenMP threads (below, waking them costs more than
  // the work); 0: always (tests). The grid is the same for any thread count.
  void set_parallel_from(std::ptrdiff_t points) { parallel_from_ = points; }

 private:
  // The (up to 3) distinct cells along one axis next to cell c, in `out`; returns how many.
  int neighbour_cells(int axis, int c, int out[3]) const;
  template <class Visit>
  void for_each_neighbour_periodic(std::uint32_t a, Visit&& visit) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d inverse_edge_ = Eigen::Vector3d::Zero();  // 1/m, per axis
  double cell_size_ = 0.0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::array<bool, 3> periodic_{false, false, false};
  bool any_periodic_ = false;
  std::ptrdiff_t parallel_from_ = kDefaultParallelFrom;
  std::vector<std::uint32_t> cell_of_;     // cell of each point
  std::vector<std::uint32_t> cell_start_;  // points of cell c are sorted_[start[c], start[c+1])
  std::vector<std::uint32_t> sorted_;      // point ids ordered by cell
};

template <class Visit>
void CellGrid::for_each_candidate_pair(Visit&& visit) const {
  if (any_periodic_) {
    // Wrapped neighbourhoods do not split into the 13 forward offsets below when an axis has
    // fewer than 3 cells; each point's full neighbourhood, the pair taken from its lower id.
    const auto n = static_cast<std::uint32_t>(cell_of_.size());
    for (std::uint32_t a = 0; a < n; ++a)
      for_each_neighbour_periodic(a, [&](std::uint32_t b) { if (a < b) visit(a, b); });
    return;
  }
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

template <class Visit>
void CellGrid::for_each_neighbour(std::uint32_t a, Visit&& visit) const {
  if (any_periodic_) {
    for_each_neighbour_periodic(a, visit);
    return;
  }
  const std::uint32_t c = cell_of_[a];
  const int cx = static_cast<int>(c % static_cast<std::uint32_t>(nx_));
  const int cy = static_cast<int>((c / static_cast<std::uint32_t>(nx_)) % static_cast<std::uint32_t>(ny_));
  const int cz = static_cast<int>(c / (static_cast<std::uint32_t>(nx_) * static_cast<std::uint32_t>(ny_)));
  for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, nz_ - 1); ++z) {
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, ny_ - 1); ++y) {
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, nx_ - 1); ++x) {
        const std::size_t d = (static_cast<std::size_t>(z) * ny_ + y) * nx_ + x;
        for (std::uint32_t k = cell_start_[d]; k < cell_start_[d + 1]; ++k) {
          if (sorted_[k] != a) visit(sorted_[k]);
        }
      }
    }
  }
}

template <class Visit>
void CellGrid::for_each_neighbour_periodic(std::uint32_t a, Visit&& visit) const {
  const std::uint32_t c = cell_of_[a];
  const auto ux = static_cast<std::uint32_t>(nx_), uy = static_cast<std::uint32_t>(ny_);
  int xs[3], ys[3], zs[3];
  const int kx = neighbour_cells(0, static_cast<int>(c % ux), xs);
  const int ky = neighbour_cells(1, static_cast<int>((c / ux) % uy), ys);
  const int kz = neighbour_cells(2, static_cast<int>(c / (ux * uy)), zs);
  for (int iz = 0; iz < kz; ++iz) {
    for (int iy = 0; iy < ky; ++iy) {
      for (int ix = 0; ix < kx; ++ix) {
        const std::size_t d = (static_cast<std::size_t>(zs[iz]) * ny_ + ys[iy]) * nx_ + xs[ix];
        for (std::uint32_t k = cell_start_[d]; k < cell_start_[d + 1]; ++k) {
          if (sorted_[k] != a) visit(sorted_[k]);
        }
      }
    }
  }
}

inline int CellGrid::neighbour_cells(int axis, int c, int out[3]) const {
  const int n = axis == 0 ? nx_ : axis == 1 ? ny_ : nz_;
  int k = 0;
  if (!periodic_[static_cast<std::size_t>(axis)]) {
    for (int x = std::max(c - 1, 0); x <= std::min(c + 1, n - 1); ++x) out[k++] = x;
  } else if (n >= 3) {
    out[k++] = c == 0 ? n - 1 : c - 1;
    out[k++] = c;
    out[k++] = c == n - 1 ? 0 : c + 1;
  } else {
    for (int x = 0; x < n; ++x) out[k++] = x;
  }
  return k;
}

}  // namespace tmdem::mechanics
