#include "coupling/studies/SparseExactReference.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "coupling/studies/ChebyshevExpSeries.h"

namespace tmdem::coupling {

namespace {

using LD = long double;

// gamma_n = n u / (1 - n u): the classic bound of n roundings of unit roundoff u.
LD gamma_n(std::size_t n, LD u) {
  const LD nu = LD(n) * u;
  return nu / (1.0L - nu);
}

template <class Real>
constexpr LD unit_roundoff = LD(std::numeric_limits<Real>::epsilon()) / 2.0L;

// X = I + kappa S^-1 K S^-1 on the free particles, compressed rows, with what the error bound
// needs of it.
template <class Real>
struct ScaledOperator {
  std::vector<std::size_t> row_start;
  std::vector<std::uint32_t> column;  // free index
  std::vector<Real> value;
  std::size_t max_row_terms = 0;
  LD abs_norm = 0.0L;     // >= |(|X|)|_2
  LD error_norm = 0.0L;   // >= |X stored - X exact|_2
};

// Builds X for kappa = 2 / |lambda|; false when Gershgorin cannot place the stored X's spectrum
// above -1 (the caller widens lambda). Each row is checked in the similar C^-1 K form (rows
// scaled by s_j / s_i), whose discs are far tighter than the symmetric form's when the
// capacities differ by orders of magnitude. A diagonal whose row reaches past 1 by rounding is
// lowered by that much (counted in error_norm), so that the stored X's spectrum is in [-1, 1].
template <class Real>
bool build_operator(const AffineThermalSystem& sys, const std::vector<std::int64_t>& free_of,
                    const std::vector<std::size_t>& node_of, const std::vector<Real>& s, LD kappa,
                    ScaledOperator<Real>& X) {
  constexpr LD u = unit_roundoff<Real>;
  constexpr LD uld = unit_roundoff<LD>;
  const auto& K = sys.K_W_per_K;
  X = {};
  X.row_start.push_back(0);
  for (std::size_t f = 0; f < node_of.size(); ++f) {
    const auto i = Eigen::Index(node_of[f]);
    const Real Ci = Real(sys.C_J_per_K[std::size_t(i)]);
    LD diag_K = 0.0L;
    std::size_t diag_at = X.value.size();
    X.column.push_back(std::uint32_t(f));
    X.value.push_back(Real(1));
    LD off_scaled = 0.0L;  // sum_j |X_ij| s_j / s_i
    for (Eigen::SparseMatrix<LD, Eigen::RowMajor>::InnerIterator it(K, i); it; ++it) {
      if (it.col() == i) {
        diag_K += it.value();
        continue;
      }
      const std::int64_t g = free_of[std::size_t(it.col())];
      if (g < 0) continue;  // held: a constant
      const Real Cj = Real(sys.C_J_per_K[std::size_t(it.col())]);
      // The same operations in the same order for (i, j) and (j, i): X stays exactly symmetric.
      const Real x = Real(kappa) * Real(it.value()) / std::sqrt(std::min(Ci, Cj) * std::max(Ci, Cj));
      X.column.push_back(std::uint32_t(g));
      X.value.push_back(x);
      off_scaled += std::abs(LD(x)) * LD(s[std::size_t(g)]) / LD(s[f]);
    }
    const Real d = Real(1) + Real(kappa) * Real(diag_K) / Ci;
    const std::size_t terms = X.value.size() - diag_at;
    X.max_row_terms = std::max(X.max_row_terms, terms);
    const LD sum_err = gamma_n(terms + 4, uld) * (std::abs(LD(d)) + off_scaled);
    LD lowered = 0.0L;
    Real dd = d;
    if (LD(d) + off_scaled + sum_err > 1.0L) {
      lowered = (LD(d) + off_scaled + sum_err - 1.0L) + 4.0L * u * (std::abs(LD(d)) + 1.0L);
      dd = Real(LD(d) - lowered);
    }
    if (LD(dd) - off_scaled - sum_err < -1.0L) return false;
    X.value[diag_at] = dd;
    X.row_start.push_back(X.value.size());
    X.abs_norm = std::max(X.abs_norm, (std::abs(LD(dd)) + off_scaled) * (1.0L + gamma_n(terms + 4, uld)));
    // Stored minus exact, by row: the off-diagonal products (6 roundings), K's summing, the
    // diagonal's own roundings and the lowering.
    const LD kd = std::abs(kappa * diag_K / LD(Ci));
    const LD row_err = gamma_n(6, u) * off_scaled +
                       kappa * sys.K_rounding_W_per_K[std::size_t(i)] / LD(Ci) * (1.0L + 8.0L * uld) +
                       gamma_n(4, u) * (1.0L + kd) + lowered + 2.0L * u * std::abs(LD(dd));
    X.error_norm = std::max(X.error_norm, row_err);
  }
  return true;
}

template <class Real>
SparseExactReference solve(const AffineThermalSystem& sys, std::span<const double> T0,
                           double t_s, const SparseExactOptions& opt) {
  constexpr LD u = unit_roundoff<Real>;
  constexpr LD uld = unit_roundoff<LD>;
  constexpr LD ud = unit_roundoff<double>;
  const std::size_t n = sys.size();
  if (T0.size() != n) throw std::invalid_argument("sparse exact reference: T0 has the wrong size");
  if (!(t_s >= 0.0) || !std::isfinite(t_s))
    throw std::invalid_argument("sparse exact reference: the time must be finite and >= 0");
  const auto& K = sys.K_W_per_K;

  std::vector<std::int64_t> free_of(n, -1);
  std::vector<std::size_t> node_of;
  for (std::size_t i = 0; i < n; ++i) {
    if (sys.held[i]) continue;
    const double C = sys.C_J_per_K[i];
    if (!(C > 0.0) || !std::isfinite(C))
      throw std::domain_error("sparse exact reference: a heat capacity is not positive");
    free_of[i] = std::int64_t(node_of.size());
    node_of.push_back(i);
  }
  const std::size_t nf = node_of.size();
  if (nf > std::numeric_limits<std::uint32_t>::max())
    throw std::domain_error("sparse exact reference: too many particles");

  SparseExactReference out;
  out.T_K.assign(T0.begin(), T0.end());

  // Checks and Gershgorin's lower bound of C^-1 K on the free particles. Held particles' columns
  // go to the affine part q (W) at their fixed temperatures, with T_ref's share (T = T_ref + theta).
  double T_lo = std::numeric_limits<double>::infinity(), T_hi = -T_lo, T_held = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {
    T_lo = std::min(T_lo, T0[node_of[f]]);
    T_hi = std::max(T_hi, T0[node_of[f]]);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (sys.held[i]) T_held = std::max(T_held, std::abs(T0[i]));
  const LD T_ref = nf ? (LD(T_lo) + LD(T_hi)) / 2.0L : 0.0L;
  LD lambda_lo = 0.0L;
  bool any_coupling = false;
  // The maximum principle: each particle relaxes towards its neighbours and its own ambient
  // q0_i / leak_i (walls, fluid, held neighbours and source together), so T(t) stays within
  // the range of T0, the held temperatures and those ambients. Without a leak but with a
  // source there is no such range (bounded = false).
  LD range_lo = T_lo, range_hi = T_hi, capacity_sum = 0.0L;
  bool bounded = true;
  std::vector<LD> q(nf, 0.0L), q_err(nf, 0.0L);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto i = Eigen::Index(node_of[f]);
    LD diag = 0.0L, off = 0.0L, q_abs = std::abs(LD(sys.f_W[std::size_t(i)]));
    LD q0 = sys.f_W[std::size_t(i)];
    std::size_t terms = 0;
    q[f] = sys.f_W[std::size_t(i)];
    for (Eigen::SparseMatrix<LD, Eigen::RowMajor>::InnerIterator it(K, i); it; ++it) {
      ++terms;
      const auto j = Eigen::Index(it.col());
      if (free_of[std::size_t(j)] < 0) {
        q[f] += it.value() * LD(T0[std::size_t(j)]);
        q0 += it.value() * LD(T0[std::size_t(j)]);
        q_abs += std::abs(it.value() * LD(T0[std::size_t(j)]));
        continue;
      }
      q[f] += T_ref * it.value();
      q_abs += std::abs(T_ref * it.value());
      if (j == i) {
        diag += it.value();
        continue;
      }
      if (it.value() < 0.0L)
        throw std::domain_error("sparse exact reference: a negative conductance between particles");
      if (K.coeff(j, i) != it.value())
        throw std::domain_error("sparse exact reference: K is not symmetric on the free particles");
      off += it.value();
    }
    if (diag + off > 2.0L * sys.K_rounding_W_per_K[std::size_t(i)])
      throw std::domain_error("sparse exact reference: K is not dissipative (a row sum > 0)");
    any_coupling = any_coupling || diag != 0.0L || off != 0.0L;
    const LD leak = -(diag + off);
    if (leak > 4.0L * sys.K_rounding_W_per_K[std::size_t(i)]) {
      range_lo = std::min(range_lo, q0 / leak);
      range_hi = std::max(range_hi, q0 / leak);
    } else if (q0 != 0.0L) {
      bounded = false;
    }
    capacity_sum += LD(sys.C_J_per_K[std::size_t(i)]);
    lambda_lo = std::min(lambda_lo, (diag - off) / LD(sys.C_J_per_K[std::size_t(i)]));
    q_err[f] = gamma_n(terms + 3, uld) * q_abs +
               sys.K_rounding_W_per_K[std::size_t(i)] * std::max(std::abs(T_ref), LD(T_held));
  }
  if (nf == 0 || t_s == 0.0) return out;

  const LD t = t_s;
  LD max_T = 0.0L, max_conversion = 0.0L;
  auto finish = [&](std::size_t f, LD T) {
    out.T_K[node_of[f]] = double(T);
    if (!std::isfinite(out.T_K[node_of[f]]))
      throw std::runtime_error("sparse exact reference: a temperature is not finite");
    max_T = std::max(max_T, std::abs(T));
  };

  if (!any_coupling) {
    // No conductance on the free particles: T = T0 + t q / C exactly (K's free columns are
    // all zero, so q has no share of T_ref).
    for (std::size_t f = 0; f < nf; ++f) {
      const LD C = sys.C_J_per_K[node_of[f]], T0f = T0[node_of[f]];
      finish(f, T0f + t * q[f] / C);
      max_conversion =
          std::max(max_conversion, gamma_n(4, uld) * (std::abs(T0f) + t * std::abs(q[f]) / C) +
                                       t * q_err[f] / C);
    }
    out.data_bound_K = double(max_conversion + ud * max_T * 1.01L);
    out.error_bound_K = out.data_bound_K;
    return out;
  }

  std::vector<Real> s(nf);
  LD s_min = std::numeric_limits<LD>::infinity();
  for (std::size_t f = 0; f < nf; ++f) {
    s[f] = std::sqrt(Real(sys.C_J_per_K[node_of[f]]));
    s_min = std::min(s_min, LD(s[f]));
  }
  // lambda a little wider than Gershgorin's (its own rounding), wider again if the stored X
  // needs it.
  ScaledOperator<Real> X;
  LD lambda = lambda_lo * (1.0L + 1e-12L);
  while (!build_operator(sys, free_of, node_of, s, 2.0L / -lambda, X)) {
    lambda *= 1.0L + 1e-9L;
    if (lambda < lambda_lo * (1.0L + 1e-6L))
      throw std::domain_error("sparse exact reference: the spectrum bound does not hold");
  }
  const LD kappa = 2.0L / -lambda;
  const LD a = t * -lambda / 2.0L;
  out.lambda_lo_per_s = double(lambda);
  out.a = double(a);

  std::vector<Real> y0(nf), beta(nf);
  LD norm_y0 = 0.0L, norm_beta = 0.0L, norm_dbeta = 0.0L;
  for (std::size_t f = 0; f < nf; ++f) {
    y0[f] = s[f] * Real(LD(T0[node_of[f]]) - T_ref);
    beta[f] = Real(kappa * q[f] / LD(s[f]));
    norm_y0 += LD(y0[f]) * LD(y0[f]);
    norm_beta += LD(beta[f]) * LD(beta[f]);
    const LD db = kappa * q_err[f] / LD(s[f]) + gamma_n(3, u) * std::abs(LD(beta[f]));
    norm_dbeta += db * db;
  }
  const LD norm_slack = 1.0L + gamma_n(nf + 2, uld);
  norm_y0 = std::sqrt(norm_y0) * norm_slack;
  norm_beta = std::sqrt(norm_beta) * norm_slack;
  norm_dbeta = std::sqrt(norm_dbeta) * norm_slack;

  // Terms: the fewest whose tail bound is below the tolerance.
  const ChebyshevExpSeries series(a);
  const LD target = LD(opt.truncation_tolerance) * (norm_y0 + a * norm_beta);
  std::size_t m = series.size() - 1;
  for (std::size_t k = 0; k + 1 < series.size(); ++k)
    if (series.tail(k + 1, 0) * norm_y0 + series.tail(k + 1, 2) * norm_beta <= target) {
      m = k;
      break;
    }
  if (opt.max_terms > 0) m = std::min(m, opt.max_terms - 1);
  std::vector<Real> c(m + 1);
  for (std::size_t k = 0; k <= m; ++k) c[k] = Real(series.coefficient(k));

  // The recurrence w_(k+1) = 2 (X w_k + beta) - w_(k-1), w_0 = y0, w_1 = X y0 + beta, summing
  // c_k w_k as it goes; the norms of the computed w_k feed the rounding bound.
  std::vector<Real> w_prev = y0, w(nf), acc(nf);
  std::vector<LD> w_norm(m + 1, 0.0L), local_error(m, 0.0L);
  for (std::size_t f = 0; f < nf; ++f) acc[f] = c[0] * y0[f];
  w_norm[0] = norm_y0;
  const auto* rs = X.row_start.data();
  const auto* col = X.column.data();
  const auto* val = X.value.data();
  const Real* b = beta.data();
  for (std::size_t k = 0; k < m; ++k) {
    const Real ck = c[k + 1];
    LD norm2 = 0.0L;
    if (k == 0) {
      for (std::size_t f = 0; f < nf; ++f) {
        Real sum = b[f];
        for (std::size_t p = rs[f]; p < rs[f + 1]; ++p) sum += val[p] * y0[col[p]];
        w[f] = sum;
        acc[f] += ck * sum;
        norm2 += LD(sum) * LD(sum);
      }
      local_error[0] = gamma_n(X.max_row_terms + 2, u) * (X.abs_norm * w_norm[0] + norm_beta);
    } else {
      Real* older = w_prev.data();  // becomes w_(k+1) in place
      const Real* cur = w.data();
      for (std::size_t f = 0; f < nf; ++f) {
        Real sum = b[f];
        for (std::size_t p = rs[f]; p < rs[f + 1]; ++p) sum += val[p] * cur[col[p]];
        const Real next = Real(2) * sum - older[f];
        older[f] = next;
        acc[f] += ck * next;
        norm2 += LD(next) * LD(next);
      }
      w_prev.swap(w);
      local_error[k] = gamma_n(X.max_row_terms + 3, u) *
                       (2.0L * X.abs_norm * w_norm[k] + 2.0L * norm_beta + w_norm[k - 1]);
    }
    w_norm[k + 1] = std::sqrt(norm2) * norm_slack;  // after k = 0: w_prev = w_0, w = w_1
  }
  out.products = m;

  // Rounding: f_j reaches sum_k c_k w_k through U_(k-j-1)(X), norm <= k - j:
  // D_j = sum_(j<k<=m) c_k (k - j) = D_(j+1) + sum_(j<k<=m) c_k.
  LD propagated = 0.0L, D = 0.0L, S0 = 0.0L, weighted = 0.0L;
  for (std::size_t j = m; j-- > 0;) {
    S0 += LD(c[j + 1]);
    D += S0;
    propagated += local_error[j] * D;
  }
  for (std::size_t k = 0; k <= m; ++k) weighted += LD(c[k]) * w_norm[k];
  const LD summing = gamma_n(m + 2, u) * weighted;
  const LD coefficients = (series.relative_error() + u) * weighted;
  const LD truncation = series.tail(m + 1, 0) * norm_y0 + series.tail(m + 1, 2) * norm_beta;
  // max_s |y(s)|_2: |y0| + t |g| always; sqrt(sum C) max |T - T_ref| by the maximum principle.
  LD y_max = norm_y0 + a * norm_beta;
  if (bounded)
    y_max = std::min(y_max, std::sqrt(capacity_sum) *
                                std::max(range_hi - T_ref, T_ref - range_lo) * (1.0L + 1e-9L));
  const LD data = a * (X.error_norm * y_max + norm_dbeta) + gamma_n(3, u) * norm_y0;

  for (std::size_t f = 0; f < nf; ++f) {
    const LD theta = LD(acc[f]) / LD(s[f]);
    finish(f, T_ref + theta);
    max_conversion = std::max(max_conversion, 2.0L * uld * std::abs(theta));
  }
  const LD to_K = (1.0L + 4.0L * uld) / s_min;
  out.truncation_bound_K = double(truncation * to_K);
  out.rounding_bound_K = double((propagated + summing + coefficients) * to_K);
  out.data_bound_K = double(data * to_K + max_conversion + (uld + ud) * max_T * 1.01L);
  out.error_bound_K = double((LD(out.truncation_bound_K) + LD(out.rounding_bound_K) +
                              LD(out.data_bound_K)) * (1.0L + 1e-12L));
  return out;
}

}  // namespace

SparseExactReference sparse_exact_temperatures(const AffineThermalSystem& system,
                                               std::span<const double> T0_K, double t_s,
                                               const SparseExactOptions& options) {
  return options.long_double_arithmetic ? solve<LD>(system, T0_K, t_s, options)
                                        : solve<double>(system, T0_K, t_s, options);
}

}  // namespace tmdem::coupling
