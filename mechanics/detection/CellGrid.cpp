#include "mechanics/detection/CellGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tmdem::mechanics {

void CellGrid::build(const std::vector<Eigen::Vector3d>& points, double min_cell_size_m) {
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
  // Cap the cell count at a few per point so that an outlier cannot make the grid huge; the
  // pair count stays O(N) for any reasonably compact packing.
  const double max_cells = 4.0 * static_cast<double>(n) + 64.0;
  double cell = min_cell_size_m;
  auto cells_along = [&](double extent, double size) { return std::floor(extent / size) + 1.0; };
  for (;;) {
    const Eigen::Vector3d extent = hi - lo;
    const double total = cells_along(extent.x(), cell) * cells_along(extent.y(), cell) *
                         cells_along(extent.z(), cell);
    if (total <= max_cells) break;
    cell *= std::max(1.01, std::cbrt(total / max_cells));
  }
  origin_ = lo;
  cell_size_ = cell;
  nx_ = static_cast<int>(cells_along(hi.x() - lo.x(), cell));
  ny_ = static_cast<int>(cells_along(hi.y() - lo.y(), cell));
  nz_ = static_cast<int>(cells_along(hi.z() - lo.z(), cell));
  const std::size_t cells = static_cast<std::size_t>(nx_) * ny_ * nz_;

  cell_of_.resize(n);
  cell_start_.assign(cells + 1, 0);
  sorted_.resize(n);
  const double inv = 1.0 / cell;
  // Cells of the points: one write per point, so threads cannot change the answer.
  const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) if (count >= parallel_from_)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const Eigen::Vector3d r = (points[i] - origin_) * inv;
    const int x = std::min(static_cast<int>(r.x()), nx_ - 1);
    const int y = std::min(static_cast<int>(r.y()), ny_ - 1);
    const int z = std::min(static_cast<int>(r.z()), nz_ - 1);
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
