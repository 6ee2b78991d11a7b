// The whole accuracy study (`tmdem study accuracy` at its defaults: 12 explicit rungs,
// cvode/klu, cvode/pcg, ida/klu, ida/pcg at rtol 1e-2 ... 1e-10, the budgets of 60 s a run and
// 180 s in all) on the two 3D beds of about 25,000 particles where KLU's fill-in made the study
// last 4-6 minutes before its runs were predicted (issue 40): the target is 4 minutes.
//   BM_AccuracyStudy/0  stiff lattice: examples/lattice_constant.toml at 29 x 29 x 29 = 24,389
//                       particles, constant_conductance 1.5 W/K (C/H = 0.01 s), 10 s
//                       (docs/benchmarks.md "Choosing the linear solver")
//   BM_AccuracyStudy/1  stiff slab: examples/accuracy/stiff_bed.toml widened to 56 x 8 x 56 =
//                       25,088 particles, 300 s
// Timed: the scene's frozen thermal problem built, then the study (reference included), as the
// command does after reading the scene. One iteration each (2-3 minutes).
//
// Counters: particles; study_s (wall) and cpu_s (process CPU) of one study; made and skipped
//   runs; klu_made (klu runs made); klu_factorisation_s (one KLU factorisation, as the study
//   timed it: the machine's load shows here).
// Run with OMP_NUM_THREADS=2 (the thermal side is single-threaded; the figure of the issue is
// the study with both cores available).
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/BenchFrozenProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "coupling/studies/AccuracyStudy.h"
#include "thermal/integrators/KluFactorisationCost.h"

namespace {

using namespace tmdem;
using namespace tmdem::coupling;

Scene bed(int which) {
  const std::string examples = std::string(TMDEM_SOURCE_DIR) + "/examples/";
  if (which == 0)
    return load_scene_file(examples + "lattice_constant.toml",
                           {"generate[0].counts=[29,29,29]", "simulation.duration=10",
                            "thermal.constant_conductance=1.5"});
  return load_scene_file(examples + "accuracy/stiff_bed.toml",
                         {"generate[0].counts=[56,8,56]", "assign[0].box.max=[1.0,0.0035,1.0]",
                          "assign[1].box.max=[1.0,0.0075,1.0]",
                          "assign[2].box.max=[1.0,0.0115,1.0]",
                          "assign[3].box.max=[1.0,0.0155,1.0]"});
}

void BM_AccuracyStudy(benchmark::State& state) {
  const Scene scene = bed(int(state.range(0)));
  const AccuracyStudyOptions options;  // the command's defaults
  AccuracyStudyResult result;
  double wall = 0.0, cpu = 0.0, factorisation_s = 0.0;
  for (auto _ : state) {
    const double cpu_start = bench::process_cpu_s();
    const auto start = std::chrono::steady_clock::now();
    auto problem = bench::quiet_frozen_problem(scene);
    const auto base = bench::settings_for(scene, *problem.system);
    result = run_accuracy_study(*problem.system, problem.T0_K, scene.duration_s, base, options,
                                &std::cerr);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = bench::process_cpu_s() - cpu_start;
    state.PauseTiming();
    factorisation_s = thermal::time_klu_factorisation(problem.system->pattern()).factorisation_s;
    state.ResumeTiming();
  }
  int made = 0, skipped = 0, klu_made = 0;
  for (const auto& r : result.runs) {
    made += r.ok;
    skipped += r.skipped;
    klu_made += r.ok && r.linear_solver == "klu";
  }
  state.counters["particles"] = double(result.nodes);
  state.counters["study_s"] = wall;
  state.counters["cpu_s"] = cpu;
  state.counters["made"] = made;
  state.counters["skipped"] = skipped;
  state.counters["klu_made"] = klu_made;
  state.counters["klu_factorisation_s"] = factorisation_s;
}
BENCHMARK(BM_AccuracyStudy)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
