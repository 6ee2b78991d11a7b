// The Chebyshev coefficients of exp(a (x - 1)) (coupling/studies/ChebyshevExpSeries.h) against
// the standard library's Bessel functions, and their tail bounds against the sums they bound.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/studies/ChebyshevExpSeries.h"

namespace tmdem::coupling {
namespace {

// 2 e^-a I_k(a) (k >= 1), e^-a I_0(a), from std::cyl_bessel_i (double; I_k(a) overflows past
// a ~ 700, so only moderate a here; at a = 400, k ~ 300 it is off by 1e-12, the series by 1e-20
// (mpmath, below)).
double expected(double a, std::size_t k) {
  return (k == 0 ? 1.0 : 2.0) * std::exp(-a) * std::cyl_bessel_i(double(k), a);
}

TEST(ChebyshevExpSeries, MatchesBesselFunctions) {
  for (double a : {0.25, 3.0, 40.0, 400.0}) {
    const ChebyshevExpSeries series(a);
    long double sum = 0.0L, second_moment = 0.0L;
    for (std::size_t k = 0; k < series.size(); ++k) {
      sum += series.coefficient(k);
      second_moment += series.coefficient(k) * (long double)k * (long double)k;
      const double want = expected(a, k);
      if (want > 1e-250) {
        EXPECT_NEAR(double(series.coefficient(k)) / want, 1.0, 5e-12) << "a = " << a << ", k = " << k;
      }
    }
    EXPECT_NEAR(double(sum), 1.0, 1e-18) << "a = " << a;  // exp(0) at x = 1
    // d/dx exp(a (x - 1)) at x = 1 is a; T_k'(1) = k^2.
    EXPECT_NEAR(double(second_moment / a), 1.0, 1e-15) << "a = " << a;
    // Held far enough: the last held coefficient is negligible.
    EXPECT_LT(double(series.coefficient(series.size() - 1)), 1e-40) << "a = " << a;
  }
}

// Long double values from mpmath 1.3.0 (40 digits): 2 e^-a besseli(k, a) (k >= 1, halved for 0).
TEST(ChebyshevExpSeries, MatchesHighPrecisionValues) {
  struct Value {
    long double a;
    std::size_t k;
    long double c;
  };
  for (const Value& v : {Value{400.0L, 0, 0.01995335628193998987129679L},
                         Value{400.0L, 100, 1.561436089420981887702375e-7L},
                         Value{400.0L, 285, 1.241593166295223112528239e-44L},
                         Value{125000.0L, 0, 0.0011283802954797574179754L},
                         Value{125000.0L, 1000, 4.133423248949384730191016e-5L}}) {
    const ChebyshevExpSeries series(v.a);
    EXPECT_NEAR(double(series.coefficient(v.k) / v.c - 1.0L), 0.0, 1e-17) << double(v.a) << " " << v.k;
  }
}

// tail(from, p) >= sum_(k >= from) c_k k^p, summed from the library's values well past the end.
TEST(ChebyshevExpSeries, TailBoundsHold) {
  for (double a : {3.0, 40.0, 400.0}) {
    const ChebyshevExpSeries series(a);
    for (std::size_t from : {std::size_t(1), std::size_t(std::sqrt(a)), std::size_t(4 * std::sqrt(a) + 5),
                             series.size() - 1, series.size() + 10}) {
      long double t0 = 0.0L, t2 = 0.0L;
      for (std::size_t k = from; k < series.size() + 400; ++k) {
        const long double c = expected(a, k);
        t0 += c;
        t2 += c * (long double)k * (long double)k;
      }
      EXPECT_GE(series.tail(from, 0), t0 * (1.0L - 1e-12L)) << "a = " << a << ", from " << from;
      EXPECT_GE(series.tail(from, 2), t2 * (1.0L - 1e-12L)) << "a = " << a << ", from " << from;
      // ...and not by much where the tail is not negligible.
      if (t0 > 1e-200L && from < series.size()) {
        EXPECT_LE(series.tail(from, 0), t0 * 1.01L) << "a = " << a << ", from " << from;
      }
    }
  }
}

// The ratio bound the tail relies on (Amos 1974), checked against the library.
TEST(ChebyshevExpSeries, BesselRatioBoundHolds) {
  for (double a : {0.5, 7.0, 90.0, 600.0})
    for (double k : {0.0, 1.0, 5.0, 30.0, 100.0}) {
      const double r = std::cyl_bessel_i(k + 1.0, a) / std::cyl_bessel_i(k, a);
      if (!std::isfinite(r)) continue;  // both below the smallest double
      EXPECT_LE(r, a / (k + std::sqrt(k * k + a * a)) * (1.0 + 1e-13)) << "a = " << a << ", k = " << k;
    }
}

TEST(ChebyshevExpSeries, ZeroArgumentIsTheIdentity) {
  const ChebyshevExpSeries series(0.0L);
  ASSERT_EQ(series.size(), 1u);
  EXPECT_EQ(series.coefficient(0), 1.0L);
  EXPECT_EQ(series.tail(1, 0), 0.0L);
  EXPECT_THROW(ChebyshevExpSeries(-1.0L), std::invalid_argument);
}

// Large arguments (the stiff beds: a ~ 1e5 to 1e7) keep the identities without overflow.
TEST(ChebyshevExpSeries, LargeArgument) {
  for (long double a : {1.25e5L, 3.6e7L}) {
    const ChebyshevExpSeries series(a);
    long double sum = 0.0L, second = 0.0L;
    for (std::size_t k = 0; k < series.size(); ++k) {
      sum += series.coefficient(k);
      second += series.coefficient(k) * (long double)k * (long double)k;
    }
    EXPECT_NEAR(double(sum), 1.0, 1e-15);
    EXPECT_NEAR(double(second / a), 1.0, 1e-12);
    // About sqrt(210 a) held: the square-root cost.
    EXPECT_LT(double(series.size()), 16.0 * std::sqrt(double(a)));
  }
}

}  // namespace
}  // namespace tmdem::coupling
