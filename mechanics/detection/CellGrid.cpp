#include "mechanics/detection/CellGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tmdem::mechanics {

void CellGrid::build(const std::vector<Eigen::Vector3d>& points, double min_cell_size_m,
                     const PeriodicBox& box) {
  if (!(min_cell_size_m > 0.0) || !std::isfinite(min_cell_size_m)) {
    throw std::invalid_argument("CellGrid: cell size must be positive and finite");
  }
  if (points.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("CellGrid: too many points");
  }
  const std::size_t n = points.size();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(0.0), hi = lo;
  if (n > 0) {
    lo = hi = points[0];
    for (const auto& p : points) {
      if (!p.allFinite()) throw std::invalid_argument("CellGrid: non-finite position");
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  // A periodic axis spans its whole period, whatever the points' extent.
  periodic_ = box.periodic;
  any_periodic_ = box.any();
  for (int a = 0; a < 3; ++a) {
    if (!box.along(a)) continue;
    if (!(box.length(a) > 0.0) || !std::isfinite(box.length(a)))
      throw std::invalid_argument("CellGrid: a periodic axis needs high > low, finite");
    lo[a] = box.low[a];
    hi[a] = box.high[a];
  }
  // Cap the cell count at a few per point so that an outlier cannot make the grid huge; the
  // pair count stays O(N) for any reasonably compact packing.
  const double max_cells = 4.0 * static_cast<double>(n) + 64.0;
  double cell = min_cell_size_m;
  // An open axis: cells from the lowest point, the last one reaching past the highest. A
  // periodic axis: whole cells in the period (at least one), each at least `size` wide.
  auto cells_along_axis = [&](int a, double size) {
    const double extent = hi[a] - lo[a];
    return box.along(a) ? std::max(std::floor(extent / size), 1.0) : std::floor(extent / size) + 1.0;
  };
  for (;;) {
    const double total = cells_along_axis(0, cell) * cells_along_axis(1, cell) * cells_along_axis(2, cell);
    if (total <= max_cells) break;
    cell *= std::max(1.01, std::cbrt(total / max_cells));
  }
  origin_ = lo;
  cell_size_ = cell;
  nx_ = static_cast<int>(cells_along_axis(0, cell));
  ny_ = static_cast<int>(cells_along_axis(1, cell));
  nz_ = static_cast<int>(cells_along_axis(2, cell));
  for (int a = 0; a < 3; ++a) {
    const double cells = a == 0 ? nx_ : a == 1 ? ny_ : nz_;
    inverse_edge_[a] = box.along(a) ? cells / (hi[a] - lo[a]) : 1.0 / cell;
    if (box.along(a)) cell_size_ = std::min(cell_size_, (hi[a] - lo[a]) / cells);
  }
  const std::size_t cells = static_cast<std::size_t>(nx_) * ny_ * nz_;

  cell_of_.resize(n);
  cell_start_.assign(cells + 1, 0);
  sorted_.resize(n);
  // Cells of the points: one write per point, so threads cannot change the answer.
  const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) if (count >= parallel_from_)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const Eigen::Vector3d r = (points[i] - origin_).cwiseProduct(inverse_edge_);
    // max(.., 0): a wrapped point a rounding below a periodic axis' low end.
    const int x = std::max(std::min(static_cast<int>(r.x()), nx_ - 1), 0);
    const int y = std::max(std::min(static_cast<int>(r.y()), ny_ - 1), 0);
    const int z = std::max(std::min(static_cast<int>(r.z()), nz_ - 1), 0);
    cell_of_[i] = static_cast<std::uint32_t>((static_cast<std::size_t>(z) * ny_ + y) * nx_ + x);
  }
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  // Fill back to front so that points keep increasing id order inside each cell.
  for (std::size_t i = n; i-- > 0;) {
    // cell_start_[c + 1] is used as a running "end" cursor, restored by the fill itself.
    sorted_[--cell_start_[cell_of_[i] + 1]] = static_cast<std::uint32_t>(i);
  }
  // After the fill, cell_start_[c + 1] holds the start of cell c; shift back by one.
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c] = cell_start_[c + 1];
  cell_start_[cells] = static_cast<std::uint32_t>(n);
}

}  // namespace tmdem::mechanics
