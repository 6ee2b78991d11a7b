#include "coupling/studies/AccuracyRunForecast.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "coupling/common/FormattedNumber.h"
#include "thermal/integrators/IntegratorKind.h"

namespace tmdem::coupling {

namespace {

struct Counts {
  double steps = 0.0, setups = 0.0, rhs = 0.0;
};

Counts counts_of(const AccuracyRun& r) {
  return {double(r.steps), double(r.linear_setups), double(r.rhs_evals)};
}

bool is_klu(const std::string& solver) {
  return solver == thermal::name_of(thermal::LinearSolverKind::Klu);
}

std::string text(const char* format, double x) { return formatted_number(format, x); }

std::string run_name(const AccuracyRun& r) {
  return r.label() + " rtol " + text("%.0e", r.parameter) + " (" + text("%.3g", r.wall_time_s) +
         " s)";
}

// The cheapest finished run of `method` at `rtol` with a linear solver other than `solver`.
const AccuracyRun* sibling(const std::string& method, const std::string& solver, double rtol,
                           const std::vector<AccuracyRun>& done) {
  const AccuracyRun* best = nullptr;
  for (const auto& r : done)
    if (r.ok && r.method == method && r.linear_solver != solver && r.parameter == rtol &&
        (!best || r.wall_time_s < best->wall_time_s))
      best = &r;
  return best;
}

// The finished run of method/solver at rtol; null if none.
const AccuracyRun* sibling_with(const std::string& method, const std::string& solver, double rtol,
                                const std::vector<AccuracyRun>& done) {
  for (const auto& r : done)
    if (r.ok && r.method == method && r.linear_solver == solver && r.parameter == rtol) return &r;
  return nullptr;
}

// The tightest finished run of `method` with a linear solver other than `solver`; null if none.
const AccuracyRun* tightest_sibling(const std::string& method, const std::string& solver,
                                   const std::vector<AccuracyRun>& done) {
  const AccuracyRun* best = nullptr;
  for (const auto& r : done)
    if (r.ok && r.method == method && r.linear_solver != solver &&
        (!best || r.parameter < best->parameter))
      best = &r;
  return best;
}

// The finished runs of method/solver looser than `rtol`, tightest first.
std::vector<const AccuracyRun*> looser_runs(const std::string& method, const std::string& solver,
                                            double rtol, const std::vector<AccuracyRun>& done) {
  std::vector<const AccuracyRun*> runs;
  for (const auto& r : done)
    if (r.ok && r.method == method && r.linear_solver == solver && r.parameter > rtol)
      runs.push_back(&r);
  std::sort(runs.begin(), runs.end(),
            [](const AccuracyRun* a, const AccuracyRun* b) { return a->parameter < b->parameter; });
  return runs;
}

// Steps' growth per factor 100 in tolerance between the two tightest of `runs` (at least 1).
double growth_per_100(const std::vector<const AccuracyRun*>& runs) {
  if (runs.size() < 2 || runs[0]->steps <= 0 || runs[1]->steps <= 0) return kDefaultGrowthPer100;
  const double decades = std::log10(runs[1]->parameter / runs[0]->parameter);
  return std::max(1.0, std::pow(double(runs[0]->steps) / double(runs[1]->steps), 2.0 / decades));
}

}  // namespace

AccuracyRunForecaster::AccuracyRunForecaster(std::optional<thermal::KluFactorisationCost> klu)
    : klu_(klu) {}

RunForecast AccuracyRunForecaster::implicit_run(const std::string& method,
                                                const std::string& solver, double rtol,
                                                const std::vector<AccuracyRun>& done) const {
  RunForecast f;
  const bool klu = is_klu(solver);
  if (klu && !klu_) return f;
  const bool timed = klu && std::isfinite(klu_->factorisation_s);
  // klu's model: timed, setups x factorisation + rhs x solve; analysed only, the setups alone.
  const auto model = [&](const Counts& c) {
    return timed ? c.setups * klu_->factorisation_s + c.rhs * klu_->solve_s : c.setups;
  };

  // A finished run of the same integrator at rtol with another solver, the cheapest.
  const AccuracyRun* from = sibling(method, solver, rtol, done);
  const auto looser = looser_runs(method, solver, rtol, done);

  if (!looser.empty()) {
    // The method's own last run, scaled by how much more the same sibling did from its
    // tolerance to rtol (klu: by the model, others: by right-hand sides), else by the growth of
    // its own steps.
    const AccuracyRun& last = *looser[0];
    const auto cost = [&](const AccuracyRun& r) {
      return klu ? model(counts_of(r)) : double(r.rhs_evals);
    };
    const AccuracyRun* from_before =
        from ? sibling_with(method, from->linear_solver, last.parameter, done) : nullptr;
    double ratio = 0.0;
    std::string why;
    if (from_before && cost(*from_before) > 0.0) {
      ratio = cost(*from) / cost(*from_before);
      why = "as " + from->label() + " from rtol " + text("%.0e", last.parameter);
    } else {
      ratio = std::pow(growth_per_100(looser), std::log10(last.parameter / rtol) / 2.0);
      why = "its steps' growth";
    }
    ratio = std::max(1.0, ratio);
    f.wall_time_s = last.wall_time_s * ratio;
    f.basis = run_name(last) + " x " + text("%.3g", ratio) + ", " + why;
    return f;
  }
  // Its counts and the rest of its work (right-hand sides, Jacobians, error tests: the wall
  // time of a run without KLU): the sibling at rtol, else the sibling's tightest run grown.
  std::optional<Counts> counts;
  double rest_s = 0.0;
  std::string counts_basis;
  if (from) {
    counts = counts_of(*from);
    rest_s = from->wall_time_s;
    counts_basis = "the counts of " + run_name(*from);
  } else if (const AccuracyRun* other = tightest_sibling(method, solver, done)) {
    const auto runs = looser_runs(method, other->linear_solver, rtol, done);
    const double growth = std::pow(growth_per_100(runs), std::log10(other->parameter / rtol) / 2.0);
    counts = Counts{other->steps * growth, other->linear_setups * growth, other->rhs_evals * growth};
    rest_s = other->wall_time_s * growth;
    counts_basis = "the counts of " + run_name(*other) + " grown " + text("%.3g", growth) + "x";
  }
  if (!klu) return f;  // an iterative method's first run: made unpredicted
  const double setups = counts ? std::max(1.0, counts->setups) : 1.0;
  if (!timed) {
    f.wall_time_s = setups * klu_->flops / kKluFastestFlopsPerSecond;
    f.basis = "at least " + text("%.0f", setups) + " KLU factorisations of " +
              text("%.3g", klu_->flops) + " flops at " + text("%.2g", kKluFastestFlopsPerSecond) +
              " flops/s" + (counts ? ", " + counts_basis : "");
    return f;
  }
  if (!counts) {
    f.wall_time_s = klu_->factorisation_s;
    f.basis = "one KLU factorisation as timed (a lower bound)";
    return f;
  }
  f.wall_time_s = model(*counts) + rest_s;
  f.basis = text("%.0f", counts->setups) + " KLU factorisations of " +
            text("%.3g", klu_->factorisation_s) + " s and " + text("%.0f", counts->rhs) +
            " solves of " + text("%.3g", klu_->solve_s) + " s as timed, " + counts_basis;
  return f;
}

RunForecast AccuracyRunForecaster::explicit_run(double work, double work_per_step,
                                                const std::vector<AccuracyRun>& done,
                                                double probe_seconds_per_unit) const {
  RunForecast f;
  const AccuracyRun* finest = nullptr;
  for (const auto& r : done)
    if (r.ok && r.is_explicit() && r.steps > 0 && (!finest || r.parameter < finest->parameter))
      finest = &r;
  if (finest && work_per_step > 0.0) {
    const double per_unit = finest->wall_time_s / (double(finest->steps) * work_per_step);
    f.wall_time_s = work * per_unit;
    f.basis = text("%.3g", work) + " work units at the cost of explicit h = " +
              text("%.3e", finest->parameter) + " s";
  } else if (probe_seconds_per_unit == probe_seconds_per_unit) {
    f.wall_time_s = work * probe_seconds_per_unit;
    f.basis = text("%.3g", work) + " work units at the cost of a probe of explicit steps";
  }
  return f;
}

}  // namespace tmdem::coupling
