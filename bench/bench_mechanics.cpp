// Mechanics benchmarks: contact detection against N (expect O(N)), and the Gauss-Seidel
// contact solver on piles at rest (cost per contact per sweep, sweeps to tolerance).
//
// Piles: a simple-cubic lattice of touching spheres (R = 1 mm, steel, mu = 0.3) standing on
// a floor under gravity, 10 layers high and n x n wide, so that N = 1e3, 1e4, 1e5 have the
// same depth; it is at rest from the first step, so no settling run is needed. "cold" is
// the first step (reactions start from zero), the timed steps are warm-started.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "BenchLattice.h"
#include "mechanics/detection/ContactDetector.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/detection/TouchingPairs.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

namespace {

using tmdem::bench::kRadius;
using tmdem::bench::lattice;
using tmdem::bench::width_for;

// Candidate-table rebuild (grid + pair list + sort + warm-start map) for a dense packing.
void BM_DetectionRebuild(benchmark::State& state) {
  const ParticleSet set = lattice(width_for(state.range(0), 10), 10);
  const std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0)};
  ContactDetector detector(0.1 * kRadius, 2.0 * kRadius);
  double seconds = 0.0;
  std::int64_t calls = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    detector.invalidate();
    detector.update(set, walls, {});
    benchmark::DoNotOptimize(detector.pairs().data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++calls;
  }
  state.counters["particles"] = static_cast<double>(set.size());
  state.counters["pairs"] = static_cast<double>(detector.pairs().size());
  state.counters["ns_per_particle"] =
      seconds * 1e9 / (static_cast<double>(calls) * static_cast<double>(set.size()));
}
BENCHMARK(BM_DetectionRebuild)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// The per-step check when nothing moved (what a step costs when no rebuild is needed).
void BM_DetectionCheck(benchmark::State& state) {
  const ParticleSet set = lattice(width_for(state.range(0), 10), 10);
  ContactDetector detector(0.1 * kRadius, 2.0 * kRadius);
  detector.update(set, {}, {});
  for (auto _ : state) benchmark::DoNotOptimize(detector.update(set, {}, {}));
  state.counters["particles"] = static_cast<double>(set.size());
}
BENCHMARK(BM_DetectionCheck)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);

// Geometry-only search used by mechanics = "off" (allocates its result each call).
void BM_FindTouchingPairs(benchmark::State& state) {
  const ParticleSet set = lattice(width_for(state.range(0), 10), 10);
  const std::vector<Wall> walls = {Wall::through({0, 0, 0}, {0, 1, 0}, 0)};
  std::size_t pairs = 0;
  for (auto _ : state) {
    const auto found = find_touching_pairs(set, walls);
    pairs = found.size();
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["particles"] = static_cast<double>(set.size());
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_FindTouchingPairs)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// One NSCD step of a pile at rest; counters give sweeps and ns per contact per sweep.
void BM_NscdStepAtRest(benchmark::State& state) {
  NscdParameters parameters;  // tolerance 1e-6, theta 0.5, h = 1e-3
  parameters.solver = "nlgs";  // the figures in docs/benchmarks.md are Gauss-Seidel's
  parameters.max_iterations = 100000;
  const int nx = width_for(state.range(0), 10);
  NscdIntegrator sim(lattice(nx, 10), {Material{7800.0, 2.1e11, 0.3, 0.3}},
                     {Wall::through({0, 0, 0}, {0, 1, 0}, 0)}, Vector3d(0, -9.81, 0), 3,
                     parameters);
  const StepReport cold = sim.step();
  for (int warm = 0; warm < 5; ++warm) sim.step();
  std::int64_t sweeps = 0, contact_sweeps = 0, steps = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const StepReport report = sim.step();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    sweeps += report.sweeps;
    contact_sweeps += static_cast<std::int64_t>(report.sweeps) * report.candidates;
    ++steps;
  }
  state.counters["particles"] = static_cast<double>(sim.particles().size());
  state.counters["candidates"] = static_cast<double>(sim.detector().pairs().size());
  state.counters["active"] = static_cast<double>(sim.contacts().size());
  state.counters["cold_sweeps"] = cold.sweeps;
  state.counters["cold_converged"] = cold.converged ? 1 : 0;
  state.counters["warm_sweeps"] = static_cast<double>(sweeps) / static_cast<double>(steps);
  // Whole step time (detection check, setup, sweeps, update) per contact visit: an upper
  // bound of the pure sweep cost, close to it when sweeps dominate.
  state.counters["ns_per_contact_sweep"] = seconds * 1e9 / static_cast<double>(contact_sweeps);
  state.counters["max_penetration_m"] = sim.stats().max_penetration_m;
}
BENCHMARK(BM_NscdStepAtRest)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)
    ->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
