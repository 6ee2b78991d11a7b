#pragma once
// y(x) from points (x_k, y_k), linear between them and clamped outside (y_0 before x_0, the last
// y after the last x). Used for wall temperatures that follow a table in time.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace tmdem::thermal {

struct PiecewiseLinearTable {
  std::vector<double> x;  // strictly increasing, at least one point
  std::vector<double> y;

  double operator()(double at) const {
    if (at <= x.front()) return y.front();
    if (at >= x.back()) return y.back();
    const auto k = std::size_t(std::upper_bound(x.begin(), x.end(), at) - x.begin());  // x[k-1] <= at < x[k]
    const double s = (at - x[k - 1]) / (x[k] - x[k - 1]);
    return y[k - 1] + s * (y[k] - y[k - 1]);
  }
  double max_y() const { return *std::max_element(y.begin(), y.end()); }
};

}  // namespace tmdem::thermal
