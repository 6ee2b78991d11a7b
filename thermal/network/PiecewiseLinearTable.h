#pragma once
// y(x) from points (x_k, y_k), linear between them and clamped outside (y_0 before x_0, the last
// y after the last x). Used for wall temperatures that follow a table in time, and for material
// properties that follow temperature (k(T), c(T)); one point is a constant.
#include <algorithm>
#include <cmath>
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
  double min_y() const { return *std::min_element(y.begin(), y.end()); }

  // dy/dx at `at`: the slope of the piece [x_k-1, x_k) holding it, 0 outside the points (where
  // y is clamped). At a point the right-hand slope.
  double slope(double at) const {
    if (x.size() < 2 || at < x.front() || at >= x.back()) return 0.0;
    const auto k = std::size_t(std::upper_bound(x.begin(), x.end(), at) - x.begin());
    return (y[k] - y[k - 1]) / (x[k] - x[k - 1]);
  }

  // The integral of y from 0 to `at` (exact: trapezoids between points, y_0 below x_0, the last
  // y above the last x), e.g. the Kirchhoff transform of k(T) or the enthalpy of c(T).
  double integral(double at) const {
    if (at <= x.front()) return y.front() * at;
    double sum = y.front() * x.front();
    for (std::size_t k = 1; k < x.size(); ++k) {
      if (at <= x[k]) return sum + 0.5 * (y[k - 1] + (*this)(at)) * (at - x[k - 1]);
      sum += 0.5 * (y[k - 1] + y[k]) * (x[k] - x[k - 1]);
    }
    return sum + y.back() * (at - x.back());
  }

  // The x at which integral(x) = value, for y > 0 everywhere (integral increasing): the inverse
  // of the enthalpy m int c dT, exact up to round-off (a quadratic per piece).
  double inverse_integral(double value) const {
    double sum = y.front() * x.front();
    if (value <= sum) return value / y.front();
    for (std::size_t k = 1; k < x.size(); ++k) {
      const double width = x[k] - x[k - 1];
      const double piece = 0.5 * (y[k - 1] + y[k]) * width;
      if (value <= sum + piece) {
        // y_(k-1) d + s d^2 / 2 = r, in the form without cancellation.
        const double r = value - sum, s = (y[k] - y[k - 1]) / width;
        return x[k - 1] + 2.0 * r / (y[k - 1] + std::sqrt(y[k - 1] * y[k - 1] + 2.0 * s * r));
      }
      sum += piece;
    }
    return x.back() + (value - sum) / y.back();
  }
};

}  // namespace tmdem::thermal
