// Cost of advancing the thermal network of a simple-cubic lattice (6-neighbour contacts, equal
// conductances and capacities) over a fixed simulated time, per integrator:
//   cvode/klu (BDF + sparse direct), cvode/pcg (BDF + CG preconditioned by IC(0), matrix-free),
//   cvode/amg (BDF + CG preconditioned by a hypre BoomerAMG V-cycle) and explicit (forward Euler
//   at 0.9 of its stability bound).
// Lattices of 10^3, 22^3, 46^3 and 100^3 nodes (1e3 .. 1e6). The x = 0 face touches an
// isothermal wall at 400 K, the x = L-1 face one at 300 K; the lattice starts at 300 K, so a
// front diffuses in from one side (a smooth transient, as in a heated packing).
//
// Counters:
//   nodes, steps (integrator steps of one run), rhs_evals, jac_evals, lin_setups (KLU
//   refactorizations / preconditioner set-ups), lin_iters (CG iterations),
//   ns_node_step       wall time of one run / (nodes * steps),
//   cpu_ns_node_step   the same with the process CPU time (the machine may be shared),
//   peak_rss_MB        peak resident-set growth during one run (VmHWM after the run minus VmRSS
//                      before it; VmHWM reset through /proc/self/clear_refs), i.e. everything the
//                      integrator allocates (SUNDIALS vectors, KLU factors, CG work vectors),
//   model_MB           bytes of the main arrays owned by the system: network + CSC pattern.
// Runs that would take far too long (KLU on the 46^3 and 100^3 lattices: fill-in) are skipped
// with the reason in the table. Whole program: ~30 s on 2 cores.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "thermal/integrators/BoomerAmgPreconditioner.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/system/ThermalSystem.h"

namespace {

using namespace tmdem::thermal;

constexpr double kC_J_per_K = 1e-3;     // every node
constexpr double kH_W_per_K = 1e-4;     // every contact and wall contact: H / C = 0.1 1/s
constexpr double kStiffH_W_per_K = 0.1;  // the stiff_lattice cases: H / C = 100 1/s
// 100 s of simulated time: 67 explicit steps (0.9 of the 1.67 s bound), ~60 BDF steps; the 1e6
// cvode/pcg case then takes ~20 s.
constexpr double kSimulatedTime_s = 100.0;

ThermalNetwork lattice(int L, double H_W_per_K = kH_W_per_K) {
  ThermalNetwork net;
  const std::size_t n = std::size_t(L) * L * L;
  net.resize_nodes(n);
  std::fill(net.heat_capacity_J_per_K.begin(), net.heat_capacity_J_per_K.end(), kC_J_per_K);
  auto id = [L](int x, int y, int z) { return std::int32_t((std::int64_t(z) * L + y) * L + x); };
  net.edge_a.reserve(3 * n);
  net.edge_b.reserve(3 * n);
  net.edge_conductance_W_per_K.reserve(3 * n);
  for (int z = 0; z < L; ++z)
    for (int y = 0; y < L; ++y)
      for (int x = 0; x < L; ++x) {
        if (x + 1 < L) net.add_edge(id(x, y, z), id(x + 1, y, z), H_W_per_K);
        if (y + 1 < L) net.add_edge(id(x, y, z), id(x, y + 1, z), H_W_per_K);
        if (z + 1 < L) net.add_edge(id(x, y, z), id(x, y, z + 1), H_W_per_K);
      }
  for (int z = 0; z < L; ++z)
    for (int y = 0; y < L; ++y) {
      net.add_wall_edge(id(0, y, z), 400.0, H_W_per_K);
      net.add_wall_edge(id(L - 1, y, z), 300.0, H_W_per_K);
    }
  return net;
}

template <class T>
double bytes(const std::vector<T>& v) {
  return double(v.capacity() * sizeof(T));
}

double model_bytes(const ThermalSystem& sys) {
  const auto& n = sys.network();
  const auto& p = sys.pattern();
  return bytes(n.heat_capacity_J_per_K) + bytes(n.surface_area_m2) + bytes(n.emissivity) +
         bytes(n.heat_source_W) + bytes(n.held) + bytes(n.edge_a) + bytes(n.edge_b) +
         bytes(n.edge_conductance_W_per_K) + bytes(n.wall_node) + bytes(n.wall_temperature_K) +
         bytes(n.wall_conductance_W_per_K) + bytes(p.column_start) + bytes(p.row_index) +
         bytes(p.diagonal_slot) + bytes(p.slot_ab) + bytes(p.slot_ba);
}

// kB from a line of /proc/self/status ("VmRSS:", "VmHWM:").
double status_kB(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string k(key);
  while (std::getline(in, line))
    if (line.compare(0, k.size(), k) == 0) return std::stod(line.substr(k.size()));
  return 0.0;
}

bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  return bool(out);
}

struct Method {
  const char* integrator;
  const char* solver;
};
constexpr Method kMethods[] = {
    {"cvode", "klu"}, {"cvode", "pcg"}, {"cvode", "amg"}, {"explicit", "klu"}};
constexpr int kMethodCount = int(std::size(kMethods));

// Cases known to take far too long on a 2-core machine, with the reason (measured growth).
const char* skip_reason(int method, int L) {
  if (method == 0 && L >= 46)
    return "skipped: sparse LU of a 3D lattice fills in (factor work ~n^2): 22^3 takes ~8 s per "
           "run, 46^3 would take well over 10 min, 100^3 days";
  return nullptr;
}

void BM_Lattice(benchmark::State& state, int method, int L, double H_W_per_K) {
  if (const char* why = skip_reason(method, L)) {
    state.SkipWithError(why);
    for (auto _ : state) {
    }
    return;
  }
  const auto& m = kMethods[method];
  std::vector<std::unique_ptr<HeatTransferMode>> modes;
  modes.push_back(make_heat_transfer_mode("contact_conduction", {}));
  modes.push_back(make_heat_transfer_mode("wall_conduction", {}));
  ThermalSystem sys(lattice(L, H_W_per_K), std::move(modes));
  const std::size_t n = sys.size();
  const std::vector<double> T0(n, 300.0);
  IntegratorSettings settings;  // default tolerances (1e-6), explicit at 0.9 of its bound
  settings.linear_solver = parse_linear_solver_kind(m.solver);  // the benchmark's own names

  double seconds = 0.0, cpu_seconds = 0.0, peak_MB = 0.0;
  IntegratorStats stats;
  for (auto _ : state) {
    malloc_trim(0);
    const double rss_before_kB = status_kB("VmRSS:");
    const bool peak_ok = reset_peak_rss();
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    auto integ = make_thermal_integrator(m.integrator, sys, settings);
    integ->initialize(0.0, T0, 0.0);
    integ->advance_to(kSimulatedTime_s);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu_seconds += double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    stats = integ->stats();
    benchmark::DoNotOptimize(integ->temperatures_K().data());
    if (peak_ok) peak_MB = std::max(peak_MB, (status_kB("VmHWM:") - rss_before_kB) / 1024.0);
  }
  const double runs = double(state.iterations());
  state.counters["nodes"] = double(n);
  state.counters["steps"] = double(stats.steps);
  state.counters["rhs_evals"] = double(stats.rhs_evals);
  state.counters["jac_evals"] = double(stats.jacobian_evals);
  state.counters["lin_setups"] = double(stats.linear_setups);
  state.counters["lin_iters"] = double(stats.linear_iterations);
  const double node_steps = double(n) * double(stats.steps);
  state.counters["ns_node_step"] = seconds / runs * 1e9 / node_steps;
  state.counters["cpu_ns_node_step"] = cpu_seconds / runs * 1e9 / node_steps;
  state.counters["peak_rss_MB"] = peak_MB;
  state.counters["model_MB"] = model_bytes(sys) / 1e6;
  state.SetLabel(std::string(m.integrator) + "/" + m.solver);
}

}  // namespace

int main(int argc, char** argv) {
  // One run of a large case is already seconds of work: a fixed number of runs per case (more
  // for the small ones, whose times are short) instead of Google Benchmark's 0.5 s minimum.
  // MPI and hypre start once per process (~0.3 s, BoomerAmgPreconditioner.h): not in a run's time.
  { BoomerAmgPreconditioner warm_up; }
  for (int method = 0; method < kMethodCount; ++method)
    for (int L : {10, 22, 46, 100}) {
      const auto& m = kMethods[method];
      const bool explicit_method = std::string(m.integrator) == "explicit";
      const std::string name = std::string("lattice/") + m.integrator +
                               (explicit_method ? "" : std::string("_") + m.solver) +
                               "/n=" + std::to_string(L * L * L);
      benchmark::RegisterBenchmark(name.c_str(), BM_Lattice, method, L, kH_W_per_K)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(L <= 10 ? 20 : (L <= 22 && method != 0) ? 5 : 1);
    }
  // Stiff: H / C = 100 1/s, so over the same 100 s BDF's steps grow to ~10^3-10^4 times the
  // fastest time scale, the Newton matrix I - gamma J is nearly the Laplacian, and IC(0)'s
  // CG iterations grow with the lattice's width while a V-cycle's stay flat. Implicit methods
  // only (the explicit bound is 1000x smaller).
  for (int method = 1; method <= 2; ++method)
    for (int L : {22, 46, 100}) {
      const auto& m = kMethods[method];
      const std::string name = std::string("stiff_lattice/") + m.integrator + "_" + m.solver +
                               "/n=" + std::to_string(L * L * L);
      benchmark::RegisterBenchmark(name.c_str(), BM_Lattice, method, L, kStiffH_W_per_K)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
