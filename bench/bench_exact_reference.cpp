// Cost and error bound of the accuracy study's exact reference (coupling/studies/
// SparseExactReference.h) on the stiff bed of examples/accuracy/stiff_bed.toml made wider:
// nx x 8 x nx touching spheres (r = 1 mm) in horizontal layers alternating copper and a
// material with rho c / 1000, every contact and the floor wall H = 1e-3 W/K, floor at
// 373.15 K, bed at 293.15 K, 300 s. nx = 11, 35, 112: 968, 9,800 and 100,352 particles
// (t |lambda_min| = 2.5e5 for each: the same fastest particle).
//
// Counters: nodes, products (sparse matrix-vector products = Chebyshev terms - 1),
//   bound_K (the reference's error bound), cpu_s (process CPU time of one reference),
//   and on the smallest bed dense_diff_K: max |sparse - dense matrix exponential| (the dense
//   one, O(n^3), is timed apart as BM_DenseReference).
// Run with OMP_NUM_THREADS=1 (the reference is single-threaded). Whole program: ~1 min.
#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <vector>

#include "coupling/studies/ExactThermalReference.h"
#include "coupling/studies/SparseExactReference.h"

namespace {

using namespace tmdem;

constexpr int kLayers = 8;
constexpr double kRadius_m = 1e-3;
constexpr double kH_W_per_K = 1e-3;
constexpr double kEndTime_s = 300.0;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

thermal::ThermalNetwork stiff_bed(int nx) {
  thermal::ThermalNetwork net;
  net.resize_nodes(std::size_t(nx) * kLayers * nx);
  const double V = 4.0 / 3.0 * M_PI * kRadius_m * kRadius_m * kRadius_m;
  auto id = [nx](int x, int y, int z) { return std::int64_t((std::int64_t(y) * nx + z) * nx + x); };
  for (int y = 0; y < kLayers; ++y)
    for (int z = 0; z < nx; ++z)
      for (int x = 0; x < nx; ++x) {
        const auto i = std::size_t(id(x, y, z));
        net.heat_capacity_J_per_K[i] = (y % 2 == 0 ? 3.45e6 : 3.45e3) * V;
        net.surface_area_m2[i] = 4.0 * M_PI * kRadius_m * kRadius_m;
        if (x + 1 < nx) net.add_edge(id(x, y, z), id(x + 1, y, z), kH_W_per_K);
        if (z + 1 < nx) net.add_edge(id(x, y, z), id(x, y, z + 1), kH_W_per_K);
        if (y + 1 < kLayers) net.add_edge(id(x, y, z), id(x, y + 1, z), kH_W_per_K);
        if (y == 0) net.add_wall_edge(id(x, y, z), 373.15, kH_W_per_K);
      }
  return net;
}

coupling::AffineThermalSystem stiff_system(int nx) {
  return *coupling::affine_thermal_system(stiff_bed(nx), {"contact_conduction", "wall_conduction"},
                                          {});
}

void BM_SparseReference(benchmark::State& state) {
  const int nx = int(state.range(0));
  const auto sys = stiff_system(nx);
  const std::vector<double> T0(sys.size(), 293.15);
  coupling::SparseExactReference ref;
  double cpu = 0.0;
  for (auto _ : state) {
    const double start = cpu_seconds();
    ref = coupling::sparse_exact_temperatures(sys, T0, kEndTime_s);
    cpu = cpu_seconds() - start;
    benchmark::DoNotOptimize(ref.T_K.data());
  }
  state.counters["nodes"] = double(sys.size());
  state.counters["products"] = double(ref.products);
  state.counters["a"] = ref.a;
  state.counters["bound_K"] = ref.error_bound_K;
  state.counters["cpu_s"] = cpu;
  if (sys.size() < 2000) {
    const auto dense = coupling::exact_affine_temperatures(sys, T0, kEndTime_s);
    double d = 0.0;
    for (std::size_t i = 0; i < dense.size(); ++i) d = std::max(d, std::abs(dense[i] - ref.T_K[i]));
    state.counters["dense_diff_K"] = d;
  }
}
BENCHMARK(BM_SparseReference)->Arg(11)->Arg(35)->Arg(112)->Iterations(1)->Unit(benchmark::kSecond);

void BM_DenseReference(benchmark::State& state) {
  const auto sys = stiff_system(int(state.range(0)));
  const std::vector<double> T0(sys.size(), 293.15);
  double cpu = 0.0;
  for (auto _ : state) {
    const double start = cpu_seconds();
    auto T = coupling::exact_affine_temperatures(sys, T0, kEndTime_s);
    cpu = cpu_seconds() - start;
    benchmark::DoNotOptimize(T.data());
  }
  state.counters["nodes"] = double(sys.size());
  state.counters["cpu_s"] = cpu;
}
BENCHMARK(BM_DenseReference)->Arg(11)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
