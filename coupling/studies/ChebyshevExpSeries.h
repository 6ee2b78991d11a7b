#pragma once
// The Chebyshev series of exp(a (x - 1)) on [-1, 1], for the sparse exact reference
// (coupling/studies/SparseExactReference.h):
//
//   exp(a (x - 1)) = sum_k c_k T_k(x),   c_0 = e^-a I_0(a),   c_k = 2 e^-a I_k(a)  (k >= 1)
//
// (I_k: modified Bessel functions of the first kind; the generating function
// e^(a cos t) = I_0(a) + 2 sum_k I_k(a) cos(k t)). Every c_k is positive and they sum to 1. For
// large a they fall like a Gaussian, c_k ~ 2 exp(-k^2 / (2a)) / sqrt(2 pi a), so the series
// needs about sqrt(2 a ln(1/tol)) terms: the square root of the spectral width, which is why
// the reference uses it instead of a Taylor series (a terms).
//
// The coefficients come from Miller's backward recurrence I_(k-1) = I_(k+1) + (2k/a) I_k
// (stable for I_k: the backward direction is I's dominant one), started where the series is
// below 1e-45 and normalised by c_0 + c_1 + ... = 1, in long double.
#include <cstddef>
#include <vector>

namespace tmdem::coupling {

class ChebyshevExpSeries {
 public:
  // a >= 0 (half the spectral width times the time, see SparseExactReference.h).
  explicit ChebyshevExpSeries(long double a);

  long double a() const { return a_; }
  // Coefficients held: c_0 ... c_(size - 1); the ones past those are below 1e-45.
  std::size_t size() const { return c_.size(); }
  long double coefficient(std::size_t k) const { return c_[k]; }

  // An upper bound of sum_(k >= from) c_k k^power (power 0 or 2), beyond the held coefficients
  // by the ratio bound I_(k+1)(a) / I_k(a) <= a / (k + sqrt(k^2 + a^2)) (Amos 1974), which
  // falls with k.
  long double tail(std::size_t from, int power) const;

  // An estimate of the relative error of each held coefficient from rounding in the
  // recurrence and the normalisation: 4 (size + 2) u (u = long double unit roundoff).
  long double relative_error() const;

 private:
  long double a_;
  std::vector<long double> c_;
  std::vector<long double> suffix0_, suffix2_;  // sum_(k >= i) c_k and c_k k^2
};

}  // namespace tmdem::coupling
