// Accuracy benchmark (not part of ctest): on the stiff bed (examples/accuracy/stiff_bed.toml),
// the wall time CVODE/KLU needs to reach a max error of 1e-6 K against the exact reference,
// versus the explicit update reaching the same error. Target: a ratio of at least 100.
//
//   bench_accuracy [SCENE.toml] [--target K] [--max-explicit-seconds S]
//
// CVODE/KLU: every relative tolerance 10^-4, 10^-4.5, ..., 10^-11 (atol = rtol K); the fastest
// run whose error is at most the target counts (runs under 50 ms repeated, least time kept).
// Explicit: forward Euler at 0.9 x the stability bound and at a quarter of that give the
// first-order error constant c = error / h and the cost per step; the step h = 0.9 target / c
// is then run and measured if its projected wall time is at most --max-explicit-seconds
// (default 600 s), else the projected time is reported as such.
// Also prints how far the exact reference (matrix exponential) is from CVODE/KLU at
// rtol = atol = 1e-12, a floor for the errors measured.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "coupling/studies/AccuracyStudy.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/scene/SceneLoader.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"
#include "thermal/integrators/IntegratorRegistry.h"

using namespace tmdem;
using namespace tmdem::coupling;

namespace {

double max_diff(const std::vector<double>& a, std::span<const double> b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path =
      (std::filesystem::path(__FILE__).parent_path().parent_path() / "examples" / "accuracy" /
       "stiff_bed.toml")
          .string();
  double target = 1e-6, max_explicit_s = 600.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--target" && i + 1 < argc) target = std::atof(argv[++i]);
    else if (a == "--max-explicit-seconds" && i + 1 < argc) max_explicit_s = std::atof(argv[++i]);
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: bench_accuracy [SCENE.toml] [--target K] [--max-explicit-seconds S]\n";
      return 0;
    } else scene_path = a;
  }

  const Scene scene = load_scene_file(scene_path);
  ProgressReporter progress(std::cerr, true, false);
  auto problem = build_frozen_thermal_problem(scene, progress);
  auto& system = *problem.system;
  const auto base = integrator_settings(scene, choose_linear_solver(scene, system, 1).kind);
  const double T_end = scene.duration_s;
  AccuracyStudyOptions opt;
  // The CVODE runs are short: time each 5 times and keep the least (explicit runs: once).
  opt.repeat_below_s = 5.0;
  opt.max_timings = 5;
  const AccuracyStudyOptions once;  // explicit runs: the study's rule (repeat under 50 ms)

  std::printf("scene: %s, %zu particles, end time %g s, target max error %g K\n",
              scene_path.c_str(), system.size(), T_end, target);
  const auto ref = accuracy_reference(system, problem.T0_K, T_end, base, opt);
  std::printf("reference: %s, %.3g s\n", ref.description.c_str(), ref.wall_time_s);
  {
    auto s = base;
    s.linear_solver = thermal::LinearSolverKind::Klu;
    s.relative_tolerance = s.absolute_tolerance_K = 1e-12;
    s.max_steps_per_call = 100000000L;
    auto integ = thermal::make_thermal_integrator("cvode", system, s);
    integ->initialize(0.0, problem.T0_K, 0.0);
    integ->advance_to(T_end);
    std::printf("reference vs cvode/klu at rtol = atol = 1e-12: max difference %.3e K\n",
                max_diff(ref.T_K, integ->temperatures_K()));
  }

  // CVODE/KLU: fastest run reaching the target.
  const AccuracyRun* best = nullptr;
  std::vector<AccuracyRun> cvode_runs;
  cvode_runs.reserve(20);
  for (int k = 8; k <= 22; ++k) {
    auto s = base;
    s.linear_solver = thermal::LinearSolverKind::Klu;
    s.relative_tolerance = s.absolute_tolerance_K = std::pow(10.0, -0.5 * k);
    cvode_runs.push_back(timed_accuracy_run(system, "cvode", s, problem.T0_K, T_end, ref.T_K, opt));
    const auto& r = cvode_runs.back();
    std::printf("cvode/klu rtol %.2e: error %.3e K, %.4f s (cpu %.4f s), %ld steps%s\n",
                r.parameter, r.max_error_K, r.wall_time_s, r.cpu_time_s, r.steps,
                r.ok ? "" : (" FAILED: " + r.message).c_str());
    if (r.ok && r.max_error_K <= target && (!best || r.wall_time_s < best->wall_time_s)) best = &r;
  }
  if (!best) {
    std::printf("cvode/klu did not reach %g K\n", target);
    return 1;
  }

  // Explicit: two rungs, the first-order constant, then the step that reaches the target.
  const double bound = system.explicit_stability_bound_s(base.max_temperature_K);
  std::vector<AccuracyRun> ex;
  for (double h : {0.9 * bound, 0.9 * bound / 4.0}) {
    auto s = base;
    s.explicit_step_s = h;
    ex.push_back(timed_accuracy_run(system, "explicit", s, problem.T0_K, T_end, ref.T_K, once));
    std::printf("explicit h %.4e s: error %.3e K, %.3f s (cpu %.3f s), %ld steps\n", h,
                ex.back().max_error_K, ex.back().wall_time_s, ex.back().cpu_time_s, ex.back().steps);
  }
  const double order = std::log(ex[0].max_error_K / ex[1].max_error_K) / std::log(4.0);
  const double c = ex[1].max_error_K / ex[1].parameter;
  const double wall_per_step = ex[1].wall_time_s / double(ex[1].steps);
  const double cpu_per_step = ex[1].cpu_time_s / double(ex[1].steps);
  double explicit_wall = 0.0, explicit_cpu = 0.0;
  bool projected = true;
  if (const AccuracyRun* reached = ex[0].max_error_K <= target   ? &ex[0]
                                   : ex[1].max_error_K <= target ? &ex[1]
                                                                 : nullptr) {
    explicit_wall = reached->wall_time_s;
    explicit_cpu = reached->cpu_time_s;
    projected = false;
  } else {
    const double h = 0.9 * target / c;
    const double steps = std::ceil(T_end / h);
    explicit_wall = wall_per_step * steps;
    explicit_cpu = cpu_per_step * steps;
    std::printf("explicit: observed order %.3f, error constant c = %.4g K/s, %.3g s per step "
                "(cpu %.3g s); h = 0.9 target / c = %.4e s projected at %.1f s (cpu %.1f s)\n",
                order, c, wall_per_step, cpu_per_step, h, explicit_wall, explicit_cpu);
    if (explicit_wall <= max_explicit_s) {
      auto s = base;
      s.explicit_step_s = h;
      const auto r = timed_accuracy_run(system, "explicit", s, problem.T0_K, T_end, ref.T_K, once);
      std::printf("explicit h %.4e s: error %.3e K, %.1f s (cpu %.1f s), %ld steps (measured)\n",
                  h, r.max_error_K, r.wall_time_s, r.cpu_time_s, r.steps);
      if (r.ok && r.max_error_K <= target) {
        explicit_wall = r.wall_time_s;
        explicit_cpu = r.cpu_time_s;
        projected = false;
      } else {
        std::printf("explicit: the measured run missed the target; keeping the projection\n");
      }
    } else {
      std::printf("explicit: projected time above %g s, not run\n", max_explicit_s);
    }
  }
  std::printf("\nRESULT: cvode/klu reaches %g K in %.4f s wall, %.4f s cpu (rtol %.1e, error "
              "%.2e K); explicit needs %.1f s wall, %.1f s cpu (%s): ratio %.0f wall, %.0f cpu "
              "(target >= 100)\n",
              target, best->wall_time_s, best->cpu_time_s, best->parameter, best->max_error_K,
              explicit_wall, explicit_cpu, projected ? "projected" : "measured",
              explicit_wall / best->wall_time_s, explicit_cpu / best->cpu_time_s);
  return 0;
}
