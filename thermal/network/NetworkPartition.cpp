#include "thermal/network/NetworkPartition.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

NetworkPartition NetworkPartition::slabs(std::span<const double> xyz_m, int ranks) {
  if (ranks < 1) throw std::invalid_argument("NetworkPartition: " + std::to_string(ranks) + " ranks");
  if (xyz_m.size() % 3 != 0)
    throw std::invalid_argument("NetworkPartition: positions are not 3 per node");
  const std::size_t n = xyz_m.size() / 3;
  if (n > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw std::invalid_argument("NetworkPartition: more nodes than 32-bit rows hold");
  int axis = 0;
  double widest = -1.0;
  for (int k = 0; k < 3; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < n; ++i) {
      lo = std::min(lo, xyz_m[3 * i + std::size_t(k)]);
      hi = std::max(hi, xyz_m[3 * i + std::size_t(k)]);
    }
    if (n > 0 && hi - lo > widest) widest = hi - lo, axis = k;
  }
  NetworkPartition p;
  p.axis_ = axis;
  p.order_.resize(n);
  std::iota(p.order_.begin(), p.order_.end(), 0);
  std::stable_sort(p.order_.begin(), p.order_.end(), [&](std::int32_t a, std::int32_t b) {
    return xyz_m[3 * std::size_t(a) + std::size_t(axis)] < xyz_m[3 * std::size_t(b) + std::size_t(axis)];
  });
  p.row_.resize(n);
  for (std::size_t r = 0; r < n; ++r) p.row_[std::size_t(p.order_[r])] = std::int32_t(r);
  p.first_row_.resize(std::size_t(ranks) + 1);
  const std::size_t base = n / std::size_t(ranks), extra = n % std::size_t(ranks);
  p.first_row_[0] = 0;
  for (std::size_t r = 0; r < std::size_t(ranks); ++r)
    p.first_row_[r + 1] = p.first_row_[r] + std::int32_t(base + (r < extra ? 1 : 0));
  p.owner_.resize(n);
  for (int r = 0; r < ranks; ++r)
    for (std::int32_t row = p.first_row(r); row < p.first_row(r + 1); ++row)
      p.owner_[std::size_t(p.order_[std::size_t(row)])] = r;
  return p;
}

}  // namespace tmdem::thermal
