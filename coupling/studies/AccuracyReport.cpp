#include "coupling/studies/AccuracyReport.h"

#include "coupling/common/CsvField.h"
#include "coupling/common/FormattedNumber.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

namespace tmdem::coupling {

namespace {

// The label (and method) of the explicit update's runs.
const std::string kExplicitLabel(thermal::name_of(thermal::IntegratorKind::Explicit));

std::string fmt(const char* format, double x) { return formatted_number(format, x); }

std::string parameter_text(const AccuracyRun& r) {
  return r.is_explicit() ? "h = " + fmt("%.3e", r.parameter) + " s"
                                : "rtol = " + fmt("%.0e", r.parameter);
}

std::string ratio_text(double slow_s, double fast_s) {
  if (!(fast_s > 0.0) || !(slow_s > 0.0)) return "";
  const double r = slow_s / fast_s;
  auto times = [](double x) { return fmt(x >= 100.0 ? "%.0f" : "%.3g", x) + "x"; };
  return r >= 1.0 ? times(r) + " faster than explicit" : times(1.0 / r) + " slower than explicit";
}

// Method labels in the order they first appear.
std::vector<std::string> labels_of(const std::vector<AccuracyRun>& runs) {
  std::vector<std::string> labels;
  for (const auto& r : runs)
    if (std::find(labels.begin(), labels.end(), r.label()) == labels.end())
      labels.push_back(r.label());
  return labels;
}

// The loosest (explicit: largest-step) skipped run of `label`; null if none.
const AccuracyRun* first_skipped(const std::vector<AccuracyRun>& runs, const std::string& label) {
  for (const auto& r : runs)
    if (r.skipped && r.label() == label) return &r;
  return nullptr;
}

const AccuracyRun* most_accurate(const std::vector<AccuracyRun>& runs, const std::string& label) {
  const AccuracyRun* best = nullptr;
  for (const auto& r : runs)
    if (r.ok && r.label() == label && (!best || r.max_error_K < best->max_error_K)) best = &r;
  return best;
}

}  // namespace

void write_accuracy_csv(std::ostream& out, const std::vector<AccuracyRun>& runs) {
  out << kAccuracyCsvHeader << "," << kAccuracyCsvExtension << "\n";
  for (const auto& r : runs) {
    if (!r.ok) continue;
    out << r.method << "," << r.linear_solver << "," << shortest_number(r.parameter) << ","
        << shortest_number(r.max_error_K) << "," << shortest_number(r.wall_time_s) << ","
        << r.steps << "," << r.rhs_evals << ",ok,";
    if (std::isfinite(r.predicted_wall_time_s)) out << shortest_number(r.predicted_wall_time_s);
    out << "\n";
  }
}

void write_skipped_runs_csv(std::ostream& out, const std::vector<AccuracyRun>& runs) {
  out << kSkippedRunsCsvHeader << "\n";
  for (const auto& r : runs) {
    if (!r.skipped) continue;
    out << r.method << "," << r.linear_solver << "," << shortest_number(r.parameter) << ",";
    if (std::isfinite(r.predicted_wall_time_s)) out << shortest_number(r.predicted_wall_time_s);
    out << "," << csv_quoted(r.message) << "\n";
  }
}

std::string skipped_runs_csv_path(const std::string& csv_path) {
  const std::string ext = ".csv";
  if (csv_path.size() > ext.size() && csv_path.compare(csv_path.size() - ext.size(), ext.size(), ext) == 0)
    return csv_path.substr(0, csv_path.size() - ext.size()) + ".skipped.csv";
  return csv_path + ".skipped.csv";
}

const AccuracyRun* cheapest_reaching(const std::vector<AccuracyRun>& runs, const std::string& label,
                                     double target_K) {
  const AccuracyRun* best = nullptr;
  for (const auto& r : runs)
    if (r.ok && r.label() == label && r.max_error_K <= target_K &&
        (!best || r.wall_time_s < best->wall_time_s))
      best = &r;
  return best;
}

ExplicitProjection project_explicit(const std::vector<AccuracyRun>& runs, double end_time_s,
                                    double target_K) {
  ExplicitProjection p;
  std::vector<const AccuracyRun*> ex;
  for (const auto& r : runs)
    if (r.ok && r.is_explicit() && r.steps > 0 && r.max_error_K > 0.0) ex.push_back(&r);
  if (ex.empty()) return p;
  std::sort(ex.begin(), ex.end(),
            [](const AccuracyRun* a, const AccuracyRun* b) { return a->parameter < b->parameter; });
  const AccuracyRun& basis = *ex.front();
  if (ex.size() >= 2)
    p.observed_order = std::log(ex[1]->max_error_K / ex[0]->max_error_K) /
                       std::log(ex[1]->parameter / ex[0]->parameter);
  p.available = true;
  p.basis_step_s = basis.parameter;
  p.error_constant_K_per_s = basis.max_error_K / basis.parameter;
  p.step_s = std::min(basis.parameter, target_K / p.error_constant_K_per_s);
  p.steps = std::ceil(end_time_s / p.step_s);
  p.cost_per_step_s = basis.wall_time_s / double(basis.steps);
  p.wall_time_s = p.cost_per_step_s * p.steps;
  return p;
}

void print_accuracy_report(std::ostream& out, const AccuracyStudyResult& res,
                           const AccuracyStudyOptions& opt) {
  out << "network: " << res.nodes << " particles, " << res.edges << " contact edges, "
      << res.wall_edges << " wall edges; end time (simulation.duration) " << res.end_time_s
      << " s\n";
  out << "reference: " << res.reference.description << "; "
      << fmt("%.3g", res.reference.wall_time_s) << " s\n";
  // Errors near the bound measure the reference as much as the run.
  if (std::isfinite(res.reference.error_bound_K))
    out << "reference error bound: " << fmt("%.2e", res.reference.error_bound_K)
        << " K (a max error below it is not resolved)\n";
  else
    out << "reference error bound: unknown (not an exact reference)\n";
  out << "explicit: forward Euler, h = " << opt.explicit_first_fraction
      << " x the stability bound (2/lambda_max = " << fmt("%.4g", res.stability_bound_s)
      << " s), then / " << opt.explicit_rung_factor << " per rung, " << opt.explicit_rungs
      << " rungs; work budget " << fmt("%.3g", opt.explicit_work_budget)
      << " = ceil(duration / h) x (particles + edges + wall edges) per run (a few seconds)\n";
  out << "implicit: relative tolerances";
  for (double t : opt.relative_tolerances) out << " " << fmt("%.0e", t);
  out << ", absolute tolerance = relative tolerance (K), loose to tight\n";
  out << "budgets: each run's wall time is predicted before it is made; skipped: an implicit run "
         "predicted over "
      << fmt("%.3g", opt.implicit_time_budget_s)
      << " s (--implicit-budget) or after its method's run over it, and any run predicted to end "
         "the study past "
      << fmt("%.3g", opt.study_time_budget_s) << " s (--time-budget); this study took "
      << fmt("%.3g", res.wall_time_s) << " s (reference included)\n";
  out << "timing: the integrator's initialize + advance only (steady_clock); runs under "
      << opt.repeat_below_s * 1e3 << " ms are repeated up to " << opt.max_timings
      << " times and the least time kept (cpu_time_s: thread CPU time of that run; well below "
         "the wall time means the machine was busy)\n\n";

  char line[512];
  std::snprintf(line, sizeof line, "%-9s %-6s %-18s %12s %12s %10s %10s %7s %10s\n", "method",
                "solver", "parameter", "max_error_K", "wall_time_s", "steps", "rhs_evals",
                "timings", "cpu_time_s");
  out << line;
  for (const auto& r : res.runs) {
    if (r.ok)
      std::snprintf(line, sizeof line, "%-9s %-6s %-18s %12.3e %12.3e %10ld %10ld %7d %10.3e\n",
                    r.method.c_str(), r.linear_solver.c_str(), parameter_text(r).c_str(),
                    r.max_error_K, r.wall_time_s, r.steps, r.rhs_evals, r.timings, r.cpu_time_s);
    else
      std::snprintf(line, sizeof line, "%-9s %-6s %-18s %s: %.400s\n", r.method.c_str(),
                    r.linear_solver.c_str(), parameter_text(r).c_str(),
                    r.skipped ? "skipped" : "FAILED", r.message.c_str());
    out << line;
  }

  const auto labels = labels_of(res.runs);
  for (double target : {1e-3, 1e-6}) {
    out << "\nmax error <= " << fmt("%.0e", target)
        << " K (each method's run with the least wall time that reaches it):\n";
    const AccuracyRun* ex = cheapest_reaching(res.runs, kExplicitLabel, target);
    const auto proj = project_explicit(res.runs, res.end_time_s, target);
    double explicit_time = ex ? ex->wall_time_s : (proj.available ? proj.wall_time_s : 0.0);
    const bool projected = !ex && proj.available;
    std::string fastest;
    double fastest_time = 0.0;
    for (const auto& label : labels) {
      const AccuracyRun* r = cheapest_reaching(res.runs, label, target);
      if (r) {
        std::snprintf(line, sizeof line, "  %-10s %-18s error %9.2e K  %10.3e s", label.c_str(),
                      parameter_text(*r).c_str(), r->max_error_K, r->wall_time_s);
        out << line;
        if (label != kExplicitLabel && explicit_time > 0.0)
          out << "  " << ratio_text(explicit_time, r->wall_time_s) << (projected ? " (projected)" : "");
        out << "\n";
        if (fastest.empty() || r->wall_time_s < fastest_time) {
          fastest = label;
          fastest_time = r->wall_time_s;
        }
        continue;
      }
      out << "  " << label << ": not reached";
      if (const AccuracyRun* best = most_accurate(res.runs, label))
        out << " (smallest error " << fmt("%.2e", best->max_error_K) << " K at "
            << parameter_text(*best) << ")";
      if (const AccuracyRun* skipped = first_skipped(res.runs, label)) {
        out << "; skipped from " << parameter_text(*skipped) << " on";
        if (std::isfinite(skipped->predicted_wall_time_s))
          out << " (predicted " << fmt("%.3g", skipped->predicted_wall_time_s) << " s)";
      }
      out << "\n";
      if (label == kExplicitLabel && proj.available)
        out << "    projected: h = " << fmt("%.3e", proj.step_s) << " s, "
            << fmt("%.3g", proj.steps) << " steps, " << fmt("%.3g", proj.wall_time_s)
            << " s (first order: error = c h with c = " << fmt("%.3g", proj.error_constant_K_per_s)
            << " K/s and " << fmt("%.3g", proj.cost_per_step_s)
            << " s per step from h = " << fmt("%.3e", proj.basis_step_s)
            << " s; observed order " << fmt("%.2f", proj.observed_order) << ")\n";
    }
    if (fastest.empty()) {
      out << "  no method reaches it\n";
      continue;
    }
    out << "  fastest: " << fastest;
    if (fastest != kExplicitLabel && explicit_time > 0.0)
      out << "; " << fastest << " reaches " << fmt("%.0e", target) << " K "
          << ratio_text(explicit_time, fastest_time) << (projected ? " (explicit projected)" : "");
    out << "\n";
  }
}

}  // namespace tmdem::coupling
