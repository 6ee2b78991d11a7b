// Heating on several threads (thermal/network/NodeLoopThreads.h): the fixed-order sums of the
// threaded state vectors, the row-wise Jacobian product, and whole CVODE runs of a network large
// enough to be threaded, against closed forms and against one thread.
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "tests/thermal/ThermalTestSupport.h"
#include "thermal/integrators/SundialsContext.h"
#include "thermal/integrators/ThreadedVector.h"
#include "thermal/network/NodeLoopThreads.h"

namespace tmdem::thermal::testing {
namespace threaded_heating {

// Sets OpenMP's thread count for one scope (the suite runs at OMP_NUM_THREADS=1).
class ThreadCount {
 public:
  explicit ThreadCount(int threads) : before_(omp_get_max_threads()) { omp_set_num_threads(threads); }
  ~ThreadCount() { omp_set_num_threads(before_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int before_;
};

constexpr int kSide = 37;  // 50,653 nodes: above kThreadedNodes, so the loops are threaded

int node_at(int x, int y, int z) { return (z * kSide + y) * kSide + x; }

// A simple cubic lattice of equal nodes, each joined to its six neighbours by H.
ThermalNetwork lattice(double C_J_per_K, double H_W_per_K) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(kSide * kSide * kSide));
  for (auto& c : net.heat_capacity_J_per_K) c = C_J_per_K;
  for (int z = 0; z < kSide; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        if (x + 1 < kSide) net.add_edge(node_at(x, y, z), node_at(x + 1, y, z), H_W_per_K);
        if (y + 1 < kSide) net.add_edge(node_at(x, y, z), node_at(x, y + 1, z), H_W_per_K);
        if (z + 1 < kSide) net.add_edge(node_at(x, y, z), node_at(x, y, z + 1), H_W_per_K);
      }
  return net;
}

std::vector<double> sample(std::size_t n) {  // values of both signs and many magnitudes
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = std::sin(0.37 * double(i)) * std::exp(std::cos(double(i)));
  return v;
}

TEST(ThreadedVector, OneThreadIsTheSerialVectorAndTwoSumTheirBlocksInOrder) {
  SundialsContext ctx;
  const std::size_t n = 100003;  // odd: blocks of unequal length
  const auto x = sample(n);
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = 1.0 + 0.5 * std::cos(double(i));
  auto fill = [&](N_Vector v, const std::vector<double>& values) {
    std::copy(values.begin(), values.end(), N_VGetArrayPointer(v));
  };
  auto xs = make_serial_vector(sunindextype(n), ctx, "x"), ws = make_serial_vector(sunindextype(n), ctx, "w");
  auto x1 = make_threaded_vector(sunindextype(n), 1, ctx, "x"), w1 = make_threaded_vector(sunindextype(n), 1, ctx, "w");
  auto x2 = make_threaded_vector(sunindextype(n), 2, ctx, "x"), w2 = make_threaded_vector(sunindextype(n), 2, ctx, "w");
  for (auto* v : {xs.get(), x1.get(), x2.get()}) fill(v, x);
  for (auto* v : {ws.get(), w1.get(), w2.get()}) fill(v, w);
  EXPECT_EQ(N_VDotProd(x1.get(), w1.get()), N_VDotProd(xs.get(), ws.get()));
  EXPECT_EQ(N_VWrmsNorm(x1.get(), w1.get()), N_VWrmsNorm(xs.get(), ws.get()));

  // Two threads: the two static blocks [0, n/2) and [n/2, n), each summed in index order.
  double first = 0.0, second = 0.0, first_sq = 0.0, second_sq = 0.0, abs_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double p = x[i] * w[i];
    (i < n / 2 ? first : second) += x[i] * w[i];
    (i < n / 2 ? first_sq : second_sq) += p * p;
  }
  double first_abs = 0.0, second_abs = 0.0;
  for (std::size_t i = 0; i < n; ++i) (i < n / 2 ? first_abs : second_abs) += std::abs(x[i]);
  abs_sum = first_abs + second_abs;
  EXPECT_EQ(N_VDotProd(x2.get(), w2.get()), first + second);
  EXPECT_EQ(N_VWrmsNorm(x2.get(), w2.get()), std::sqrt((first_sq + second_sq) / double(n)));
  EXPECT_EQ(N_VWL2Norm(x2.get(), w2.get()), std::sqrt(first_sq + second_sq));
  EXPECT_EQ(N_VL1Norm(x2.get()), abs_sum);
  // And to round-off the serial sums (different order, same value).
  EXPECT_NEAR(N_VDotProd(x2.get(), w2.get()), N_VDotProd(xs.get(), ws.get()), 1e-12 * double(n));

  // Clones (the solvers' work vectors) keep the fixed-order sums.
  NVectorPtr clone(N_VClone(x2.get()));
  fill(clone.get(), x);
  EXPECT_EQ(N_VDotProd(clone.get(), w2.get()), first + second);
  // A masked norm sees only the entries whose id is positive; exact on integers.
  std::vector<double> ones(n, 1.0), id(n, 0.0);
  for (std::size_t i = 0; i < n; i += 4) id[i] = 1.0;
  NVectorPtr one(N_VClone(x2.get())), mask(N_VClone(x2.get()));
  fill(one.get(), ones);
  fill(mask.get(), id);
  const double counted = double((n + 3) / 4);
  EXPECT_EQ(N_VWrmsNormMask(one.get(), one.get(), mask.get()), std::sqrt(counted / double(n)));
}

TEST(ThreadedJacobian, ProductHasTheEdgeLoopsBitsOnAnyThreadCount) {
  // Unequal conductances and capacities and two held nodes: every branch of the row loop.
  auto net = lattice(1e-3, 1e-3);
  for (std::size_t e = 0; e < net.edge_count(); ++e)
    net.edge_conductance_W_per_K[e] *= 1.0 + 0.5 * std::sin(double(e));
  for (std::size_t i = 0; i < net.node_count(); ++i)
    net.heat_capacity_J_per_K[i] *= 1.0 + 0.3 * std::cos(double(i));
  net.held[17] = 1;
  net.held[node_at(20, 20, 20)] = 1;
  auto sys = make_system(net, {"contact_conduction"});
  const std::size_t n = sys->size();
  ASSERT_GE(n, kThreadedNodes);
  std::vector<double> T(n, 300.0), scale(n);
  for (std::size_t i = 0; i < n; ++i) scale[i] = std::sqrt(net.heat_capacity_J_per_K[i]);
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  const auto v = sample(n);

  std::vector<double> one(n), two(n);
  {
    ThreadCount threads(1);
    sys->jacobian_times(J, v, one, scale);
  }
  {
    ThreadCount threads(2);
    sys->jacobian_times(J, v, two, scale);
  }
  EXPECT_EQ(one, two);

  // The loop over edges it replaced, written out: the same bits.
  std::vector<double> edges(n);
  for (std::size_t i = 0; i < n; ++i) edges[i] = net.held[i] ? 0.0 : J.diagonal_W_per_K[i] * (v[i] / scale[i]);
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    const auto a = std::size_t(net.edge_a[e]), b = std::size_t(net.edge_b[e]);
    if (net.held[a] || net.held[b]) continue;
    edges[a] += J.edge_W_per_K[e] * (v[b] / scale[b]);
    edges[b] += J.edge_W_per_K[e] * (v[a] / scale[a]);
  }
  for (std::size_t i = 0; i < n; ++i) edges[i] *= scale[i] / net.heat_capacity_J_per_K[i];
  EXPECT_EQ(one, edges);

  // And the product of the assembled matrix (pattern order, column j holds column j of S J S^-1).
  std::vector<double> values(sys->pattern().nonzeros()), csc(n, 0.0);
  sys->jacobian_values(J, values, scale);
  const auto& p = sys->pattern();
  for (std::size_t j = 0; j < n; ++j)
    for (auto k = p.column_start[j]; k < p.column_start[j + 1]; ++k)
      csc[std::size_t(p.row_index[std::size_t(k)])] += values[std::size_t(k)] * v[j];
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, std::abs(one[i] - csc[i]));
  EXPECT_LT(largest, 1e-12);
}

// Insulated lattice, T0 = 300 K + two cosine modes: T(t) = 300 K + sum A_k cos(...) exp(-lambda_k t)
// exactly, lambda = (2 H / C) (1 - cos(k pi / L)) for the mode k along one axis.
struct LatticeRun {
  std::vector<double> T;
  double boundary_heat_J = 0.0;
  long steps = 0;
};

constexpr double kC = 1e-3, kH = 1e-4, kEnd_s = 30.0;
constexpr int kModeX = 8, kModeZ = 12;  // decay to exp(-1.4) and exp(-2.9) by kEnd_s

LatticeRun run_lattice(const std::string& solver, int threads) {
  ThreadCount count(threads);
  auto sys = make_system(lattice(kC, kH), {"contact_conduction"});
  std::vector<double> T0(sys->size());
  for (int z = 0; z < kSide; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x)
        T0[std::size_t(node_at(x, y, z))] =
            300.0 + 50.0 * std::cos(kModeX * std::numbers::pi * (x + 0.5) / kSide) +
            20.0 * std::cos(kModeZ * std::numbers::pi * (z + 0.5) / kSide);
  const auto r = run(*sys, "cvode", tight_settings(solver, 1e-6), T0, kEnd_s);
  return {r.T, r.boundary_heat_J, r.stats.steps};
}

TEST(ThreadedHeating, TwoThreadsMatchTheClosedFormAndOneThreadAndRepeatTheirBits) {
  const auto one = run_lattice("pcg", 1);
  const auto two = run_lattice("pcg", 2);
  const auto again = run_lattice("pcg", 2);
  EXPECT_EQ(two.T, again.T);  // same thread count, same bits
  const auto lambda = [](int k) { return 2.0 * kH / kC * (1.0 - std::cos(k * std::numbers::pi / kSide)); };
  double from_exact = 0.0, between = 0.0, energy_one = 0.0, energy_two = 0.0;
  for (int z = 0; z < kSide; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const auto i = std::size_t(node_at(x, y, z));
        const double exact =
            300.0 +
            50.0 * std::cos(kModeX * std::numbers::pi * (x + 0.5) / kSide) * std::exp(-lambda(kModeX) * kEnd_s) +
            20.0 * std::cos(kModeZ * std::numbers::pi * (z + 0.5) / kSide) * std::exp(-lambda(kModeZ) * kEnd_s);
        from_exact = std::max(from_exact, std::abs(two.T[i] - exact));
        between = std::max(between, std::abs(two.T[i] - one.T[i]));
        energy_one += kC * (one.T[i] - 300.0);
        energy_two += kC * (two.T[i] - 300.0);
      }
  EXPECT_LT(from_exact, 1e-3);
  EXPECT_LT(between, 1e-6);  // the sums' order differs: round-off, carried by the steps
  EXPECT_EQ(one.steps, two.steps);
  // Insulated: the modes carry no net energy, so sum C (T - 300 K) stays 0 (one mode's
  // amplitude over the bed, 50 K x 50,653 x C, is 2.5 J), to the conjugate gradients' linear
  // tolerance (1e-6 of it here), and no boundary heat enters.
  EXPECT_LT(std::abs(energy_one), 1e-5);
  EXPECT_LT(std::abs(energy_two), 1e-5);
  EXPECT_EQ(two.boundary_heat_J, 0.0);
}

}  // namespace threaded_heating
}  // namespace tmdem::thermal::testing
