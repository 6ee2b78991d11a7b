#include "coupling/studies/AccuracyStudy.h"

#include "thermal/integrators/IntegratorKind.h"
#include "coupling/common/FormattedNumber.h"
#include "coupling/common/ShortestNumber.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "coupling/studies/AccuracyRunForecast.h"
#include "coupling/studies/ExactThermalReference.h"
#include "coupling/studies/SparseExactReference.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/studies/ContactRecording.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/studies/ThermalReplay.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/integrators/KluFactorisationCost.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::coupling {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double max_abs_difference(std::span<const double> T, std::span<const double> ref) {
  double e = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) {
    const double d = std::abs(T[i] - ref[i]);
    if (!std::isfinite(d)) return std::numeric_limits<double>::infinity();
    e = std::max(e, d);
  }
  return e;
}

thermal::IntegratorSettings implicit_settings(const thermal::IntegratorSettings& base,
                                              thermal::LinearSolverKind linear_solver, double rtol) {
  auto s = base;
  s.linear_solver = linear_solver;
  s.relative_tolerance = rtol;
  s.absolute_tolerance_K = rtol;
  return s;  // stop_at_each_time from base: true when a dynamic replay changes the network
}

std::string fmt_bound(double x) { return formatted_number("%.2e", x); }
std::string fmt_rtol(double x) { return formatted_number("%.0e", x); }
std::string fmt_seconds(double x) { return formatted_number("%.3g", x); }

// The forecaster, with the cost of one KLU factorisation when a klu method is studied: analysed,
// then timed unless the analysis alone puts it over a budget (at 10^6 particles the timing would
// run out of memory, as the run would). A failed analysis leaves klu runs unpredicted (they
// then fail with KLU's own error).
AccuracyRunForecaster klu_forecaster(const thermal::ThermalSystem& system,
                                     const AccuracyStudyOptions& options,
                                     Clock::time_point study_start, std::ostream* log) {
  const std::string klu(thermal::name_of(thermal::LinearSolverKind::Klu));
  bool studied = false;
  for (const auto& method : options.implicit_methods)
    studied = studied || method.solver == thermal::LinearSolverKind::Klu;
  if (!studied) return AccuracyRunForecaster();
  try {
    auto cost = thermal::analyse_klu_factorisation(system.pattern());
    const double at_least_s = cost.flops / kKluFastestFlopsPerSecond;
    if (at_least_s <= options.implicit_time_budget_s &&
        seconds_since(study_start) + at_least_s <= options.study_time_budget_s) {
      cost = thermal::time_klu_factorisation(system.pattern());
      if (log)
        *log << "study: KLU: one factorisation (" << fmt_bound(cost.flops) << " flops) took "
             << fmt_seconds(cost.factorisation_s) << " s, one solve " << fmt_seconds(cost.solve_s)
             << " s" << std::endl;
    } else if (log) {
      *log << "study: KLU: one factorisation (" << fmt_bound(cost.flops) << " flops) takes at least "
           << fmt_seconds(at_least_s) << " s, over the budget: not timed" << std::endl;
    }
    return AccuracyRunForecaster(cost);
  } catch (const thermal::ThermalSolverError& e) {
    if (log) *log << "study: KLU: " << e.what() << "; klu runs unpredicted" << std::endl;
    return AccuracyRunForecaster();
  }
}

}  // namespace

AccuracyRun timed_accuracy_run(thermal::ThermalSystem& system, const std::string& method,
                               const thermal::IntegratorSettings& settings,
                               std::span<const double> T0_K, double end_time_s,
                               std::span<const double> reference_T_K,
                               const AccuracyStudyOptions& options, const ThermalDriver& driver) {
  AccuracyRun run;
  run.method = method;
  const bool explicit_update = run.is_explicit();
  run.linear_solver =
      explicit_update ? kNoLinearSolver : std::string(thermal::name_of(settings.linear_solver));
  run.parameter = explicit_update ? settings.explicit_step_s : settings.relative_tolerance;
  run.wall_time_s = std::numeric_limits<double>::infinity();
  try {
    while (run.timings < std::max(1, options.max_timings)) {
      auto integrator = thermal::make_thermal_integrator(method, system, settings);
      const double cpu_start = thread_cpu_seconds();
      const auto start = Clock::now();
      if (driver) {
        driver(*integrator, T0_K, end_time_s, CouplingStrategy::Continue);
      } else {
        integrator->initialize(0.0, T0_K, 0.0);
        integrator->advance_to(end_time_s);
      }
      const double wall = seconds_since(start);
      const double cpu = thread_cpu_seconds() - cpu_start;
      if (run.timings == 0) {
        const auto st = integrator->stats();
        run.steps = st.steps;
        run.rhs_evals = st.rhs_evals;
        run.linear_setups = st.linear_setups;
        run.max_error_K = max_abs_difference(integrator->temperatures_K(), reference_T_K);
        if (!std::isfinite(run.max_error_K)) {
          run.ok = false;
          run.message = "non-finite temperature at the end time";
        }
      }
      ++run.timings;
      if (wall < run.wall_time_s) {
        run.wall_time_s = wall;
        run.cpu_time_s = cpu;
      }
      if (!run.ok || wall >= options.repeat_below_s) break;
    }
  } catch (const std::exception& e) {
    run.ok = false;
    run.message = e.what();
    if (!std::isfinite(run.wall_time_s)) run.wall_time_s = 0.0;
  }
  return run;
}

AccuracyReference accuracy_reference(thermal::ThermalSystem& system, std::span<const double> T0_K,
                                     double end_time_s, const thermal::IntegratorSettings& base,
                                     const AccuracyStudyOptions& options,
                                     const ThermalDriver& driver) {
  AccuracyReference ref;
  const auto start = Clock::now();
  std::optional<AffineThermalSystem> affine;
  std::string why_not;
  if (driver)
    why_not = "the contact graph changes every mechanical step";
  else
    affine = affine_thermal_system(system, &why_not);
  if (affine) {
    try {
      const auto exact = sparse_exact_temperatures(*affine, T0_K, end_time_s);
      ref.T_K = exact.T_K;
      ref.error_bound_K = exact.error_bound_K;
      ref.exact = true;
      ref.description = "exact matrix exponential of the affine system C dT/dt = K T + f (" +
                        std::to_string(system.size()) + " particles; sparse Chebyshev series, " +
                        std::to_string(exact.products + 1) + " terms for t |lambda_min| = " +
                        fmt_bound(2.0 * exact.a) + "), error bound " +
                        fmt_bound(exact.error_bound_K) + " K";
    } catch (const std::domain_error& e) {
      why_not = e.what();  // outside the method: the CVODE/KLU reference below
    } catch (const std::exception& e) {
      throw ReferenceError(std::string("the exact reference failed: ") + e.what());
    }
  }
  if (!ref.exact) {
    auto s = implicit_settings(base, thermal::LinearSolverKind::Klu, options.reference_tolerance);
    s.max_steps_per_call = std::max(s.max_steps_per_call, 100000000L);
    try {
      auto integrator = thermal::make_thermal_integrator(thermal::name_of(thermal::IntegratorKind::Cvode), system, s);
      if (driver) {
        driver(*integrator, T0_K, end_time_s, CouplingStrategy::Restart);
      } else {
        integrator->initialize(0.0, T0_K, 0.0);
        integrator->advance_to(end_time_s);
      }
      const auto T = integrator->temperatures_K();
      ref.T_K.assign(T.begin(), T.end());
    } catch (const std::exception& e) {
      throw ReferenceError(std::string("the reference run (cvode/klu, rtol = atol = ") +
                           shortest_number(options.reference_tolerance) + ") failed: " + e.what());
    }
    for (double T : ref.T_K)
      if (!std::isfinite(T))
        throw ReferenceError("the reference run (cvode/klu) gave a non-finite temperature");
    ref.description = std::string("cvode/klu") + (driver ? " restarted every mechanical step" : "") +
                      " at rtol = atol = " + shortest_number(options.reference_tolerance) +
                      " (no exact reference: " + why_not + ")";
  }
  ref.wall_time_s = seconds_since(start);
  return ref;
}

AccuracyStudyResult run_accuracy_study(thermal::ThermalSystem& system,
                                       std::span<const double> T0_K, double end_time_s,
                                       const thermal::IntegratorSettings& base,
                                       const AccuracyStudyOptions& options, std::ostream* log,
                                       const ThermalDriver& driver) {
  const auto study_start = Clock::now();
  AccuracyStudyResult result;
  result.end_time_s = end_time_s;
  const auto& net = system.network();
  result.nodes = net.node_count();
  result.edges = net.edge_count();
  result.wall_edges = net.wall_edge_count();
  result.stability_bound_s = options.stability_bound_s > 0.0
                                 ? options.stability_bound_s
                                 : system.explicit_stability_bound_s(base.max_temperature_K);

  if (log) *log << "study: computing the reference..." << std::endl;
  result.reference = accuracy_reference(system, T0_K, end_time_s, base, options, driver);
  if (log)
    *log << "study: reference: " << result.reference.description << ", "
         << result.reference.wall_time_s << " s" << std::endl;

  AccuracyRunForecaster forecaster = klu_forecaster(system, options, study_start, log);

  auto report = [&](const AccuracyRun& r) {
    if (!log) return;
    *log << "study: " << r.label() << (r.is_explicit() ? " h = " : " rtol = ")
         << r.parameter << (r.is_explicit() ? " s" : "");
    if (r.ok)
      *log << ": max error " << r.max_error_K << " K, " << r.wall_time_s << " s, " << r.steps
           << " steps" << (r.is_explicit() ? std::string()
                                : ", " + std::to_string(r.linear_setups) + " linear-solver setups")
           << (std::isfinite(r.predicted_wall_time_s)
                               ? " (predicted " + fmt_seconds(r.predicted_wall_time_s) + " s)"
                               : std::string())
           << std::endl;
    else if (r.skipped)
      *log << ": skipped: " << r.message << std::endl;
    else
      *log << ": FAILED: " << r.message << std::endl;
  };
  // A run not made: its parameters, its prediction and why.
  auto skip = [&](const std::string& method, const std::string& solver, double parameter,
                  const RunForecast& forecast, const std::string& why) {
    AccuracyRun r;
    r.method = method;
    r.linear_solver = solver;
    r.parameter = parameter;
    r.ok = false;
    r.skipped = true;
    r.predicted_wall_time_s = forecast.wall_time_s;
    r.prediction_basis = forecast.basis;
    r.message = why;
    result.runs.push_back(r);
    report(result.runs.back());
  };
  auto predicted_text = [](const RunForecast& f) {
    return "predicted " + fmt_seconds(f.wall_time_s) + " s (" + f.basis + ")";
  };
  // An interrupted study: the runs left are not made (asked once a run is due, so that a signal
  // during a run ends the study after it).
  auto interrupted = [&](const std::string& method, const std::string& solver, double parameter,
                         const RunForecast& forecast) {
    if (!options.stop || !options.stop()) return false;
    skip(method, solver, parameter, forecast, kInterruptedRunReason);
    return true;
  };
  // The study's budget: would this run end past it?
  auto past_study_budget = [&](const RunForecast& f, std::string& why) {
    const double used = seconds_since(study_start);
    if (!f.known() || used + f.wall_time_s <= options.study_time_budget_s) return false;
    why = predicted_text(f) + ", which would end the study past its " +
          fmt_seconds(options.study_time_budget_s) + " s budget (" + fmt_seconds(used) +
          " s used; --time-budget)";
    return true;
  };

  // Explicit ladder.
  const std::string explicit_name(thermal::name_of(thermal::IntegratorKind::Explicit));
  const double work_per_step = double(result.nodes + result.edges + result.wall_edges);
  double h = std::isfinite(result.stability_bound_s)
                 ? options.explicit_first_fraction * result.stability_bound_s
                 : end_time_s;
  if (options.max_explicit_step_s > 0.0) h = std::min(h, options.max_explicit_step_s);
  // Seconds per work unit of a few timed explicit steps, for the first rung's prediction (none
  // for a dynamic scene, whose network at t = 0 is not the one its rungs run on).
  double probe_seconds_per_unit = std::numeric_limits<double>::quiet_NaN();
  if (!driver && options.explicit_rungs > 0 && options.explicit_probe_steps > 0 && h > 0.0 &&
      work_per_step > 0.0) {
    auto s = base;
    s.explicit_step_s = h;
    const double probe_end = std::min(end_time_s, h * options.explicit_probe_steps);
    AccuracyStudyOptions once = options;
    once.max_timings = 1;
    const auto probe = timed_accuracy_run(system, explicit_name, s, T0_K, probe_end,
                                          result.reference.T_K, once);
    if (probe.steps > 0)
      probe_seconds_per_unit = probe.wall_time_s / (double(probe.steps) * work_per_step);
  }
  for (int k = 0; k < options.explicit_rungs; ++k, h /= options.explicit_rung_factor) {
    const double work = std::ceil(end_time_s / h) * work_per_step;
    const auto forecast =
        forecaster.explicit_run(work, work_per_step, result.runs, probe_seconds_per_unit);
    std::string why;
    if (interrupted(explicit_name, kNoLinearSolver, h, forecast)) continue;
    if (work > options.explicit_work_budget) {
      why = "projected work " + fmt_bound(work) + " over the work budget " +
            fmt_bound(options.explicit_work_budget) + " (--explicit-budget)" +
            (forecast.known() ? "; " + predicted_text(forecast) : std::string());
      skip(explicit_name, kNoLinearSolver, h, forecast, why);
      continue;
    }
    if (past_study_budget(forecast, why)) {
      skip(explicit_name, kNoLinearSolver, h, forecast, why);
      continue;
    }
    auto s = base;
    s.explicit_step_s = h;
    result.runs.push_back(timed_accuracy_run(system, explicit_name, s, T0_K, end_time_s,
                                             result.reference.T_K, options, driver));
    result.runs.back().predicted_wall_time_s = forecast.wall_time_s;
    result.runs.back().prediction_basis = forecast.basis;
    report(result.runs.back());
  }

  // Implicit methods: first those with iterative solvers, then klu (predicted from their counts
  // at the same tolerance, and the slowest on large 3D beds, so they are what the study's budget
  // cuts); within each, loose to tight, every method at a tolerance before any at the next.
  std::vector<double> tolerances = options.relative_tolerances;
  std::sort(tolerances.begin(), tolerances.end(), std::greater<>());
  std::vector<std::string> closed(options.implicit_methods.size());  // why its tighter runs are skipped
  for (const bool klu_pass : {false, true})
    for (double rtol : tolerances)
      for (std::size_t m = 0; m < options.implicit_methods.size(); ++m) {
        const auto& kinds = options.implicit_methods[m];
        if ((kinds.solver == thermal::LinearSolverKind::Klu) != klu_pass) continue;
        const std::string method = kinds.integrator_name(), solver = kinds.solver_name();
        const auto forecast = forecaster.implicit_run(method, solver, rtol, result.runs);
        std::string why;
        if (interrupted(method, solver, rtol, forecast)) continue;
        if (!closed[m].empty()) {
          skip(method, solver, rtol, forecast,
               closed[m] + (forecast.known() ? "; " + predicted_text(forecast) : std::string()));
          continue;
        }
        if (forecast.known() && forecast.wall_time_s > options.implicit_time_budget_s) {
          why = predicted_text(forecast) + ", over the " +
                fmt_seconds(options.implicit_time_budget_s) + " s budget of one run (--implicit-budget)";
          closed[m] = "a looser tolerance was skipped";
          skip(method, solver, rtol, forecast, why);
          continue;
        }
        if (past_study_budget(forecast, why)) {
          closed[m] = "a looser tolerance was skipped";
          skip(method, solver, rtol, forecast, why);
          continue;
        }
        auto run = timed_accuracy_run(system, method, implicit_settings(base, kinds.solver, rtol), T0_K,
                                      end_time_s, result.reference.T_K, options, driver);
        run.predicted_wall_time_s = forecast.wall_time_s;
        run.prediction_basis = forecast.basis;
        result.runs.push_back(run);
        report(result.runs.back());
        if (run.wall_time_s > options.implicit_time_budget_s)
          closed[m] = "rtol " + fmt_rtol(rtol) + " took " + fmt_seconds(run.wall_time_s) +
                      " s, over the " + fmt_seconds(options.implicit_time_budget_s) +
                      " s budget of one run (--implicit-budget)";
      }

  // The report's order: explicit rungs as made, then each method loose to tight.
  auto group = [&](const AccuracyRun& r) -> std::size_t {
    if (r.is_explicit()) return 0;
    for (std::size_t m = 0; m < options.implicit_methods.size(); ++m)
      if (options.implicit_methods[m].integrator_name() == r.method &&
          options.implicit_methods[m].solver_name() == r.linear_solver)
        return m + 1;
    return options.implicit_methods.size() + 1;
  };
  std::stable_sort(result.runs.begin(), result.runs.end(),
                   [&](const AccuracyRun& a, const AccuracyRun& b) {
                     const auto ga = group(a), gb = group(b);
                     if (ga != gb) return ga < gb;
                     return !a.is_explicit() && a.parameter > b.parameter;
                   });
  result.wall_time_s = seconds_since(study_start);
  return result;
}

std::vector<ImplicitMethod> parse_implicit_methods(const std::vector<std::string>& names,
                                                   std::string& problem) {
  std::vector<ImplicitMethod> methods;
  for (const auto& name : names) {
    const auto slash = name.find('/');
    try {
      if (slash == std::string::npos) throw std::invalid_argument("no \"/\" in it");
      ImplicitMethod method;
      method.integrator = thermal::parse_integrator_kind(name.substr(0, slash));
      if (method.integrator == thermal::IntegratorKind::Explicit)
        throw std::invalid_argument("the explicit update is studied by its rungs "
                                    "(--explicit-rungs), not as a method");
      const std::string solver = name.substr(slash + 1);
      if (solver == thermal::kAutoLinearSolverName)
        throw std::invalid_argument("\"auto\" chooses per run; the study compares named solvers");
      method.solver = thermal::parse_linear_solver_kind(solver);
      methods.push_back(method);
    } catch (const std::invalid_argument& e) {
      std::string valid;
      for (const auto i : {thermal::IntegratorKind::Cvode, thermal::IntegratorKind::Ida})
        for (const auto l : thermal::kLinearSolverNames)
          valid += (valid.empty() ? "" : ", ") + std::string(thermal::name_of(i)) + "/" + std::string(l);
      problem = "\"" + name + "\": " + e.what() + " (valid: " + valid + ")";
      return {};
    }
  }
  return methods;
}

}  // namespace tmdem::coupling
