// The heating target of docs/scale-out.md: a 10^6-particle bed heated for an hour at the
// defaults in at most 60 s and 2 GB on a 2-core machine. bench/lattice_1e6.toml: a 100^3
// lattice of touching steel spheres, mechanics off, the floor at 400 K, constant contact
// conductance 1e-3 W/K, 3,600 s ("auto" takes amg there).
//   BM_Heating1e6/1  one thread;  BM_Heating1e6/2  two (OpenMP: thermal/network/NodeLoopThreads.h)
// Timed: the frozen thermal problem built (contact detection, network) and the hour
// integrated, as `tmdem run` does without writing frames. One iteration each (about a minute).
//
// Counters: particles; steps; heat_s (wall) and cpu_s (process CPU) of the set-up and the
//   hour; peak_rss_MB, the process's peak so far (the /2 run's includes the /1 run's: run one
//   argument at a time with --benchmark_filter for each one's own).
#include <benchmark/benchmark.h>
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <string>

#include "bench/BenchFrozenProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "thermal/integrators/IntegratorRegistry.h"

namespace {

using namespace tmdem;
using namespace tmdem::coupling;

double peak_rss_MB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

void BM_Heating1e6(benchmark::State& state) {
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(int(state.range(0)));
  const Scene scene = load_scene_file(std::string(TMDEM_SOURCE_DIR) + "/bench/lattice_1e6.toml");
  double wall = 0.0, cpu = 0.0;
  long steps = 0;
  std::size_t particles = 0;
  for (auto _ : state) {
    const double cpu_start = bench::process_cpu_s();
    const auto start = std::chrono::steady_clock::now();
    auto problem = bench::quiet_frozen_problem(scene);
    auto integrator = thermal::make_thermal_integrator(scene.thermal.integrator, *problem.system,
                                                       bench::settings_for(scene, *problem.system));
    integrator->initialize(0.0, problem.T0_K);
    integrator->advance_to(scene.duration_s);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = bench::process_cpu_s() - cpu_start;
    steps = integrator->stats().steps;
    particles = problem.system->size();
  }
  omp_set_num_threads(threads_before);
  state.counters["particles"] = double(particles);
  state.counters["steps"] = double(steps);
  state.counters["heat_s"] = wall;
  state.counters["cpu_s"] = cpu;
  state.counters["peak_rss_MB"] = peak_rss_MB();
}
BENCHMARK(BM_Heating1e6)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
