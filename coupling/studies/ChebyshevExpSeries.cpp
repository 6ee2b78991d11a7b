#include "coupling/studies/ChebyshevExpSeries.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tmdem::coupling {

namespace {
// Miller's recurrence runs this far past the last held coefficient: its start (I_(N+1) = 0) is
// wrong near N, and the error falls by orders of magnitude per step going down.
constexpr std::size_t kMillerMargin = 24;

long double ratio_bound(long double a, std::size_t k) {  // >= I_(k+1)(a) / I_k(a)
  const long double kk = (long double)k;
  return a / (kk + std::sqrt(kk * kk + a * a));
}
}  // namespace

ChebyshevExpSeries::ChebyshevExpSeries(long double a) : a_(a) {
  if (!(a >= 0.0L) || !std::isfinite(a))
    throw std::invalid_argument("ChebyshevExpSeries: a must be finite and >= 0");
  if (a == 0.0L) {
    c_ = {1.0L};
  } else {
    // Held: up to where exp(-k^2 / 2a) (large a) or (a/2)^k / k! (small a) is below ~1e-45.
    const auto held = std::size_t(std::ceil(std::sqrt(210.0L * a))) + 30;
    const std::size_t N = held + kMillerMargin;
    std::vector<long double> v(N + 2, 0.0L);
    v[N] = 1.0L;
    for (std::size_t k = N; k >= 1; --k) {
      v[k - 1] = v[k + 1] + (2.0L * (long double)k / a) * v[k];
      if (v[k - 1] > 1e1000L)  // keep clear of overflow (small a: (2k/a)^k); the small end underflows harmlessly
        for (std::size_t j = k - 1; j <= N; ++j) v[j] *= 1e-1000L;
    }
    long double sum = v[0];
    for (std::size_t k = 1; k <= N; ++k) sum += 2.0L * v[k];
    c_.resize(held);
    c_[0] = v[0] / sum;
    for (std::size_t k = 1; k < held; ++k) c_[k] = 2.0L * v[k] / sum;
  }
  suffix0_.assign(c_.size() + 1, 0.0L);
  suffix2_.assign(c_.size() + 1, 0.0L);
  for (std::size_t k = c_.size(); k-- > 0;) {
    suffix0_[k] = suffix0_[k + 1] + c_[k];
    suffix2_[k] = suffix2_[k + 1] + c_[k] * (long double)k * (long double)k;
  }
}

long double ChebyshevExpSeries::tail(std::size_t from, int power) const {
  if (power != 0 && power != 2) throw std::invalid_argument("ChebyshevExpSeries::tail: power 0 or 2");
  const std::size_t K = c_.size();
  // Past the held coefficients: c_(K-1+j) <= c_(K-1) r^j, r the ratio bound at K - 1; from
  // j0 = max(from, K) on, the terms (times k^2) still fall by q = r ((j0+1)/j0)^2 per step.
  long double beyond = 0.0L;
  if (a_ > 0.0L) {
    const std::size_t j0 = std::max(from, K);
    const long double j = (long double)j0;
    const long double r = ratio_bound(a_, K - 1);
    const long double q = power == 0 ? r : r * ((j + 1.0L) / j) * ((j + 1.0L) / j);
    if (!(q < 1.0L)) return std::numeric_limits<long double>::infinity();
    beyond = c_[K - 1] * std::pow(r, (long double)(j0 - K + 1)) * (power == 0 ? 1.0L : j * j) /
             (1.0L - q);
  }
  if (from >= K) return beyond;
  return (power == 0 ? suffix0_[from] : suffix2_[from]) * (1.0L + relative_error()) + beyond;
}

long double ChebyshevExpSeries::relative_error() const {
  return 4.0L * (long double)(c_.size() + kMillerMargin + 2) * (LDBL_EPSILON / 2.0L);
}

}  // namespace tmdem::coupling
