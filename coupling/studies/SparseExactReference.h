#pragma once
// The accuracy study's exact reference at any size: T(t) of the affine network
// C dT/dt = K T + f (coupling/studies/ExactThermalReference.h) with a bound of its own error in
// kelvin, in time and memory linear in the matrix's nonzeros (times sqrt of the stiffness).
//
// Method. Held particles are constants. On the free ones, y = S (T - T_ref), S = diag(sqrt(C)),
// turns the system into dy/dt = B y + g with B = S^-1 K S^-1 symmetric and negative
// semi-definite (K: conductances >= 0, diagonally dominant; both checked). Gershgorin's lower
// bound lambda_lo of C^-1 K (same spectrum) maps t B onto a (X - I), X = I + (2 / |lambda_lo|) B
// with spectrum in [-1, 1] and a = t |lambda_lo| / 2. The affine part rides along in the
// augmented system [[X, beta], [0, 1]] acting on [y0; 1] (beta = 2 g / |lambda_lo|): its
// exponential's top block is exp(tB) y0 + t phi_1(tB) g whether or not B is singular (a
// cluster without a wall). exp(a (X - I)) = sum_k c_k T_k(X) (coupling/studies/
// ChebyshevExpSeries.h) is summed with the three-term recurrence, one sparse product per term,
// about sqrt(2 a ln(1/tol)) terms: t |lambda_lo| = 2.5e5 (a 300 s stiff bed) takes ~3,500.
// Arithmetic is long double (x86: 64-bit significand, u = 5.4e-20).
//
// Error bound, each part a bound in the 2-norm of y, then divided by min sqrt(C_i) for kelvin
// (|T_i error| <= |y error|_2 / sqrt(C_i)): that step is what makes the bound pessimistic by up
// to sqrt(n C_max / C_min) for errors spread over many particles.
// - truncation: sum_(k>m) c_k (|y0| + k^2 |beta|) (|T_k| <= 1 on [-1, 1]; the affine part is a
//   divided difference of T_k, at most k^2);
// - rounding in the recurrence: each step's local error f_j (standard bound gamma_(n+3) times
//   the row's |terms|, from the computed vectors' norms) propagates as U_(k-j-1)(X), at most
//   k - j: sum_j |f_j| sum_(k>j) c_k (k - j); plus the summation of c_k w_k and the
//   coefficients' estimated error (ChebyshevExpSeries::relative_error);
// - data: X, beta and y0 as stored differ from the exact ones (K summed in long double, the
//   products and square roots, 1 + ... on the diagonal), |E| by row; the ODE's solution moves
//   by at most t (|dB| max|y(s)| + |dg|), with max|y(s)| the lesser of |y0| + t |g| and, by the
//   maximum principle, sqrt(sum C) times the largest |T - T_ref| among T0 and each particle's
//   ambient (its walls, fluid, held neighbours and source: q_i / leak_i). This part dominates;
//   it is normwise, so it charges every mode the fastest mode's u |lambda_lo| perturbation;
// - the last division and conversion to double: u |T| per particle.
// The bound is rigorous for the stored operations except for the coefficients' error, an
// estimate (tested against std::cyl_bessel_i), and dB's effect, first order in u.
#include <cstddef>
#include <span>
#include <vector>

#include "coupling/studies/ExactThermalReference.h"

namespace tmdem::coupling {

struct SparseExactReference {
  std::vector<double> T_K;           // at the end time
  double error_bound_K = 0.0;        // >= max_i |T_i - T_i exact|: the sum of the parts below
  double truncation_bound_K = 0.0;
  double rounding_bound_K = 0.0;     // recurrence, summation and coefficients
  double data_bound_K = 0.0;         // stored operator and vectors, final division
  std::size_t products = 0;          // sparse matrix-vector products (terms - 1)
  double a = 0.0;                    // t |lambda_lo| / 2: the series' argument
  double lambda_lo_per_s = 0.0;      // Gershgorin's lower bound of the spectrum (<= 0)
};

struct SparseExactOptions {
  // Truncation: stop when the tail bound is below this fraction of |y0| + t |g| (2-norms).
  double truncation_tolerance = 1e-22;
  // At most this many terms (0: no limit): the tests truncate early to check that bound.
  std::size_t max_terms = 0;
  // Long double (the reference) or double: the tests run the same algorithm and bound in
  // double, whose rounding an eigendecomposition in long double can measure.
  bool long_double_arithmetic = true;
};

// T(t_s) from T(0) = T0_K. Throws std::invalid_argument for a bad size or time, and
// std::domain_error when the system is outside the method (K not symmetric on the free
// particles, not dissipative, or a capacity <= 0): the caller then needs another reference.
SparseExactReference sparse_exact_temperatures(const AffineThermalSystem& system,
                                               std::span<const double> T0_K, double t_s,
                                               const SparseExactOptions& options = {});

}  // namespace tmdem::coupling
