// The sparse exact reference (coupling/studies/SparseExactReference.h): closed forms to
// round-off, a stiff network against an eigendecomposition in long double and against the dense
// exponential, and its error bound against the error it bounds.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "coupling/studies/SparseExactReference.h"
#include "tests/coupling/studies/AffineTestNetworks.h"

namespace tmdem::coupling {
namespace {

using LD = long double;

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

using testing::convection_settings;
using testing::kAffineModes;
using testing::two_node_network;

// Two nodes, one with a source P and no wall: singular (no boundary), the mean rises as
// P t / (C1 + C2) and the difference relaxes to P / (C1 r), r = H (1/C1 + 1/C2).
std::vector<double> pair_closed_form(double C1, double C2, double H, double P, double T10,
                                     double T20, double t) {
  const LD Cs = LD(C1) + C2, r = LD(H) * (1.0L / C1 + 1.0L / C2);
  const LD Tm = (LD(C1) * T10 + LD(C2) * T20) / Cs + LD(P) * t / Cs;
  const LD d_inf = LD(P) / (C1 * r);
  const LD d = d_inf + (LD(T10) - T20 - d_inf) * std::exp(-r * LD(t));
  return {double(Tm + C2 / Cs * d), double(Tm - C1 / Cs * d)};
}

TEST(SparseExactReference, TwoNodesMatchClosedFormToRoundOff) {
  // Capacities 1e6 apart, t |A| up to 1e5: the stiff pair the dense exponential loses 5e-10 K on.
  for (double C1 : {0.015, 1e-5}) {
    const double C2 = C1 == 0.015 ? 0.004 : 10.0, H = 1e-3;
    const auto sys = affine_thermal_system(two_node_network(C1, C2, H), {"contact_conduction"}, {});
    ASSERT_TRUE(sys);
    for (double t : {0.0, 1e-3, 0.5, 20.0, 1e3}) {
      const auto ref = sparse_exact_temperatures(*sys, std::vector<double>{373.15, 293.15}, t);
      const auto want = pair_closed_form(C1, C2, H, 0.0, 373.15, 293.15, t);
      const double err = max_abs_diff(ref.T_K, want);
      EXPECT_LE(err, ref.error_bound_K) << "C1 " << C1 << ", t " << t;
      // Round-off: a double at 400 K is 6e-14 K; the long double recurrence adds ~a u.
      EXPECT_LE(err, 2e-13 + 1e-16 * ref.a) << "C1 " << C1 << ", t " << t;
      // The bound in kelvin pays sqrt(C2 / C1) = 1000 for the stiff pair.
      EXPECT_LE(ref.error_bound_K, 1e-8) << "C1 " << C1 << ", t " << t;
    }
  }
}

// No boundary at all: K is singular, the source heats the pair without limit.
TEST(SparseExactReference, SingularSystemWithSource) {
  const double C1 = 0.01, C2 = 0.03, H = 2e-3, P = 0.05;
  auto net = two_node_network(C1, C2, H);
  net.heat_source_W[0] = P;
  const auto sys = affine_thermal_system(net, {"contact_conduction", "heat_source"}, {});
  ASSERT_TRUE(sys);
  for (double t : {1.0, 30.0, 600.0}) {
    const auto ref = sparse_exact_temperatures(*sys, std::vector<double>{300.0, 310.0}, t);
    const auto want = pair_closed_form(C1, C2, H, P, 300.0, 310.0, t);
    EXPECT_LE(max_abs_diff(ref.T_K, want), ref.error_bound_K) << "t " << t;
    EXPECT_LE(max_abs_diff(ref.T_K, want), 1e-12) << "t " << t;
  }
}

// Held particle, wall, convection and source on one free particle; the held one keeps its
// temperature bit for bit.
TEST(SparseExactReference, AffineModesAndHeldParticle) {
  thermal::ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {0.02, 5.0};
  net.surface_area_m2 = {1.2e-5, 1e-5};
  net.heat_source_W[0] = 0.05;
  net.held[1] = 1;
  net.add_edge(0, 1, 3e-4);
  net.add_wall_edge(0, 350.0, 4e-4);
  const auto s = convection_settings(20.0, 280.0);
  const auto sys = affine_thermal_system(net, kAffineModes, s);
  ASSERT_TRUE(sys);
  const LD hA = 20.0L * 1.2e-5L, G = 4e-4L + hA + 3e-4L, k = G / 0.02L;
  const LD Tinf = (4e-4L * 350.0L + hA * 280.0L + 3e-4L * 420.0L + 0.05L) / G;
  for (double t : {1.0, 10.0, 100.0}) {
    const auto ref = sparse_exact_temperatures(*sys, std::vector<double>{300.0, 420.0}, t);
    const double want = double(Tinf + (300.0L - Tinf) * std::exp(-k * LD(t)));
    EXPECT_LE(std::abs(ref.T_K[0] - want), ref.error_bound_K) << "t " << t;
    EXPECT_LE(std::abs(ref.T_K[0] - want), 1e-12) << "t " << t;
    EXPECT_EQ(ref.T_K[1], 420.0);
  }
}

// A stiff network of a few hundred particles: a 6 x 6 x 6 lattice, heat capacities spread
// over four orders of magnitude, one held particle, a floor wall, convection and sources of
// both signs.
struct StiffNetwork {
  AffineThermalSystem sys;
  std::vector<double> T0;
};

StiffNetwork stiff_network() {
  constexpr int n = 6;
  thermal::ThermalNetwork net;
  net.resize_nodes(n * n * n);
  std::uint64_t state = 12345;
  auto uniform = [&] {  // deterministic, in [0, 1)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1.0p-53;
  };
  auto id = [](int x, int y, int z) { return std::int64_t(x + n * (y + n * z)); };
  std::vector<double> T0(net.node_count());
  for (std::size_t i = 0; i < net.node_count(); ++i) {
    net.heat_capacity_J_per_K[i] = 1e-5 * std::pow(1e4, uniform());
    net.surface_area_m2[i] = 1e-5;
    net.heat_source_W[i] = i % 7 == 0 ? 0.02 * (uniform() - 0.4) : 0.0;
    T0[i] = 290.0 + 20.0 * uniform();
  }
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double H = 1e-4 + 9e-4 * uniform();
        if (x + 1 < n) net.add_edge(id(x, y, z), id(x + 1, y, z), H);
        if (y + 1 < n) net.add_edge(id(x, y, z), id(x, y + 1, z), 0.7 * H);
        if (z + 1 < n) net.add_edge(id(x, y, z), id(x, y, z + 1), 1.3 * H);
        if (z == 0) net.add_wall_edge(id(x, y, z), 373.15, 5e-4);
      }
  net.held[std::size_t(id(3, 3, 5))] = 1;
  T0[std::size_t(id(3, 3, 5))] = 250.0;
  const auto s = convection_settings(15.0, 280.0);
  auto sys = affine_thermal_system(net, kAffineModes, s);
  return {*sys, T0};
}

// T(t) by the eigendecomposition of the symmetric B = S^-1 K S^-1 in long double:
// y(t) = V (e^(t L) V^T y0 + t phi_1(t L) V^T g), far more accurate than double.
std::vector<double> eigen_oracle(const AffineThermalSystem& sys, const std::vector<double>& T0,
                                 double t) {
  using Matrix = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<LD, Eigen::Dynamic, 1>;
  std::vector<std::size_t> free;
  std::vector<long> at(sys.size(), -1);
  for (std::size_t i = 0; i < sys.size(); ++i)
    if (!sys.held[i]) {
      at[i] = long(free.size());
      free.push_back(i);
    }
  const auto nf = Eigen::Index(free.size());
  Matrix B = Matrix::Zero(nf, nf);
  Vector y0(nf), g(nf), s(nf);
  for (Eigen::Index f = 0; f < nf; ++f) s(f) = std::sqrt(LD(sys.C_J_per_K[free[std::size_t(f)]]));
  for (Eigen::Index f = 0; f < nf; ++f) {
    const auto i = free[std::size_t(f)];
    y0(f) = s(f) * T0[i];
    LD q = sys.f_W[i];
    for (Eigen::SparseMatrix<LD, Eigen::RowMajor>::InnerIterator it(sys.K_W_per_K, Eigen::Index(i)); it; ++it) {
      const long j = at[std::size_t(it.col())];
      if (j < 0) q += it.value() * T0[std::size_t(it.col())];
      else B(f, j) = it.value() / (s(f) * s(j));
    }
    g(f) = q / s(f);
  }
  Eigen::SelfAdjointEigenSolver<Matrix> eig(B);
  const Matrix& V = eig.eigenvectors();
  Vector z0 = V.transpose() * y0, zg = V.transpose() * g;
  for (Eigen::Index k = 0; k < nf; ++k) {
    const LD x = t * eig.eigenvalues()(k);
    const LD phi1 = x == 0.0L ? 1.0L : std::expm1(x) / x;
    z0(k) = std::exp(x) * z0(k) + t * phi1 * zg(k);
  }
  const Vector y = V * z0;
  std::vector<double> T = T0;
  for (Eigen::Index f = 0; f < nf; ++f) T[free[std::size_t(f)]] = double(y(f) / s(f));
  return T;
}

TEST(SparseExactReference, StiffNetworkAgreesWithEigendecompositionAndDenseExponential) {
  const auto net = stiff_network();
  const double t = 20.0;
  const auto oracle = eigen_oracle(net.sys, net.T0, t);
  const auto ref = sparse_exact_temperatures(net.sys, net.T0, t);
  ASSERT_GT(ref.a, 1e3);  // stiff: about sqrt(2 a 50) products
  const double err = max_abs_diff(ref.T_K, oracle);
  EXPECT_LE(err, ref.error_bound_K);
  EXPECT_LE(ref.error_bound_K, 1e-8);
  EXPECT_GT(ref.T_K[0], 200.0);
  // The dense exponential (double, no bound of its own): off by about |tA| eps |T| (here 1e-9 K).
  const auto dense = exact_affine_temperatures(net.sys, net.T0, t);
  EXPECT_LE(max_abs_diff(dense, ref.T_K), 5e-9);
}

// The same algorithm in double: rounding now dominates, and the eigendecomposition in long
// double measures it. The bound must hold; it may be loose but not uselessly so.
TEST(SparseExactReference, RoundingBoundHoldsInDouble) {
  const auto net = stiff_network();
  for (double t : {2.0, 20.0}) {
    const auto oracle = eigen_oracle(net.sys, net.T0, t);
    SparseExactOptions opt;
    opt.long_double_arithmetic = false;
    const auto ref = sparse_exact_temperatures(net.sys, net.T0, t, opt);
    const double err = max_abs_diff(ref.T_K, oracle);
    EXPECT_LE(err, ref.error_bound_K) << "t " << t;
    EXPECT_GT(err, 0.0) << "t " << t;
    EXPECT_LE(ref.error_bound_K, 1e-5) << "t " << t;
  }
}

// Truncated early, the series misses by far more than rounding: the truncation bound holds
// and is close (the tail falls fast, so it is nearly its first term).
TEST(SparseExactReference, TruncationBoundHolds) {
  const auto net = stiff_network();
  const double t = 20.0;
  const auto oracle = eigen_oracle(net.sys, net.T0, t);
  const auto full = sparse_exact_temperatures(net.sys, net.T0, t);
  for (double fraction : {0.2, 0.3, 0.4}) {
    SparseExactOptions opt;
    opt.max_terms = std::size_t(fraction * double(full.products + 1));
    const auto ref = sparse_exact_temperatures(net.sys, net.T0, t, opt);
    const double err = max_abs_diff(ref.T_K, oracle);
    EXPECT_GT(err, 1e3 * full.error_bound_K) << fraction;
    EXPECT_LE(err, ref.error_bound_K) << fraction;
    EXPECT_GE(ref.truncation_bound_K, 0.9 * ref.error_bound_K) << fraction;
  }
}

TEST(SparseExactReference, RefusesWhatItCannotBound) {
  AffineThermalSystem sys;
  sys.C_J_per_K = {1.0, 2.0};
  sys.held = {0, 0};
  sys.f_W = {0.0, 0.0};
  sys.K_rounding_W_per_K = {0.0L, 0.0L};
  sys.K_W_per_K.resize(2, 2);
  auto with = [&](long double k01, long double k10) {
    std::vector<Eigen::Triplet<LD>> e{{0, 0, -1.0L}, {0, 1, k01}, {1, 0, k10}, {1, 1, -1.0L}};
    sys.K_W_per_K.setFromTriplets(e.begin(), e.end());
    return sparse_exact_temperatures(sys, std::vector<double>{1.0, 2.0}, 1.0);
  };
  EXPECT_NO_THROW(with(1.0L, 1.0L));
  EXPECT_THROW(with(1.0L, 0.5L), std::domain_error);   // not symmetric
  EXPECT_THROW(with(-1.0L, -1.0L), std::domain_error); // negative conductance
  sys.C_J_per_K[1] = 0.0;
  EXPECT_THROW(with(1.0L, 1.0L), std::domain_error);   // no heat capacity
  EXPECT_THROW(sparse_exact_temperatures(sys, std::vector<double>{1.0}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace tmdem::coupling
