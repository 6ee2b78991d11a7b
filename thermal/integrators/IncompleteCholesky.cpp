#include "thermal/integrators/IncompleteCholesky.h"

#include <cmath>

namespace tmdem::thermal {

void IncompleteCholesky::analyse(const JacobianPattern& pattern) {
  const std::size_t n = pattern.size();
  start_.assign(n + 1, 0);
  row_.clear();
  from_.clear();
  for (std::size_t j = 0; j < n; ++j) {
    // Rows are sorted within a column, so the diagonal comes first among rows >= j.
    for (auto p = pattern.column_start[j]; p < pattern.column_start[j + 1]; ++p) {
      if (pattern.row_index[std::size_t(p)] < std::int64_t(j)) continue;
      row_.push_back(pattern.row_index[std::size_t(p)]);
      from_.push_back(p);
    }
    start_[j + 1] = std::int64_t(row_.size());
  }
  value_.assign(row_.size(), 0.0);
  marker_.assign(n, -1);
}

bool IncompleteCholesky::factor(std::span<const double> J_values, double scale,
                                std::span<const double> shift) {
  const std::size_t n = start_.size() - 1;
  for (std::size_t q = 0; q < value_.size(); ++q) value_[q] = scale * J_values[std::size_t(from_[q])];
  for (std::size_t j = 0; j < n; ++j) value_[std::size_t(start_[j])] += shift[j];  // diagonal first
  for (std::size_t k = 0; k < n; ++k) {
    const auto first = start_[k], last = start_[k + 1];
    const double pivot = value_[std::size_t(first)];
    if (!(pivot > 0.0)) return false;
    const double d = std::sqrt(pivot);
    value_[std::size_t(first)] = d;
    for (auto p = first + 1; p < last; ++p) value_[std::size_t(p)] /= d;
    // Right-looking update of the later columns j touched by column k, within L's pattern.
    for (auto p = first + 1; p < last; ++p) {
      const auto j = std::size_t(row_[std::size_t(p)]);
      const double l_jk = value_[std::size_t(p)];
      for (auto q = start_[j]; q < start_[j + 1]; ++q) marker_[std::size_t(row_[std::size_t(q)])] = q;
      for (auto p2 = p; p2 < last; ++p2) {
        const auto slot = marker_[std::size_t(row_[std::size_t(p2)])];
        if (slot >= 0) value_[std::size_t(slot)] -= value_[std::size_t(p2)] * l_jk;
      }
      for (auto q = start_[j]; q < start_[j + 1]; ++q) marker_[std::size_t(row_[std::size_t(q)])] = -1;
    }
  }
  return true;
}

void IncompleteCholesky::solve(std::span<const double> r, std::span<double> z) {
  const std::size_t n = start_.size() - 1;
  for (std::size_t i = 0; i < n; ++i) z[i] = r[i];
  for (std::size_t k = 0; k < n; ++k) {  // L y = r, column by column
    z[k] /= value_[std::size_t(start_[k])];
    for (auto p = start_[k] + 1; p < start_[k + 1]; ++p)
      z[std::size_t(row_[std::size_t(p)])] -= value_[std::size_t(p)] * z[k];
  }
  for (std::size_t k = n; k-- > 0;) {  // L^T z = y
    double s = z[k];
    for (auto p = start_[k] + 1; p < start_[k + 1]; ++p)
      s -= value_[std::size_t(p)] * z[std::size_t(row_[std::size_t(p)])];
    z[k] = s / value_[std::size_t(start_[k])];
  }
}

}  // namespace tmdem::thermal
