#include "mechanics/solvers/NncgSolver.h"

#include "mechanics/contact/SiconosResidual.h"

#include <algorithm>
#include <limits>

#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

NncgSolver::NncgSolver(const SolverSettings& settings, const Options& options)
    : settings_(settings), options_(options) {}

int NncgSolver::stall_window() const {
  const long long window = static_cast<long long>(options_.stall_patience) * settings_.stall_sweeps;
  return static_cast<int>(std::min<long long>(window, std::numeric_limits<int>::max()));
}

template <bool WritesBodies, class Each>
double NncgSolver::over_support(Each&& each) {
  if (!sliced_run_) {
    double sum = 0.0;
    for (const std::int32_t c : support_) each(static_cast<std::size_t>(c), sum);
    return sum;
  }
  // Slab by slab, as the sweeps go (ContactSlabs.h): the slabs of one phase touch disjoint
  // particles, so their steps may write velocities at once (what only reads takes every slab
  // in one loop: one barrier); per-slab sums added in slab order.
  const std::vector<std::int32_t>& start = slabs_.slab_start();
  const std::vector<std::int32_t>& phase = slabs_.phase_start();
  slab_sums_.resize(slabs_.slab_count());
  const bool lists = sweep_.slab_lists_valid();
  const std::vector<std::int32_t>& active = sweep_.slab_active();
  const std::vector<std::int32_t>& active_end = sweep_.slab_active_end();
  constexpr int passes = WritesBodies ? ContactSlabs::kPhases : 1;
#pragma omp parallel
  for (int p = 0; p < passes; ++p) {
    const std::int32_t first = WritesBodies ? phase[p] : 0;
    const std::int32_t end = WritesBodies ? phase[p + 1] : phase[ContactSlabs::kPhases];
    if (first == end) continue;  // no piston: no barrier for its empty phase
#pragma omp for schedule(dynamic, 1)
    for (std::int32_t s = first; s < end; ++s) {
      double sum = 0.0;
      const auto visit = [&](std::int32_t c) {
        if (!in_support_[c]) return;
        double value = 0.0;  // each contact's sum apart, then added to its slab's
        each(static_cast<std::size_t>(c), value);
        sum += value;
      };
      // The support is within the slab's active list (GaussSeidelSweep::slab_active): the same
      // contacts in the same order as a scan of the whole slab, so the same bits, without
      // touching its open candidates (pour_3d: 92% of them; the scan took a fifth of the
      // solve's time, perf, 2 threads).
      if (lists) {
        for (std::int32_t k = start[s]; k < active_end[static_cast<std::size_t>(s)]; ++k) visit(active[static_cast<std::size_t>(k)]);
      } else {
        for (std::int32_t c = start[s]; c < start[s + 1]; ++c) visit(c);
      }
      slab_sums_[static_cast<std::size_t>(s)] = sum;
    }
  }
  double sum = 0.0;
  for (const double slab : slab_sums_) sum += slab;
  return sum;
}

void NncgSolver::scan_support(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                              const std::vector<Eigen::Vector3d>& m) {
  // Sliced, enter() only flags each contact in its own slot: threads may share the scan.
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
#pragma omp parallel for schedule(static) if (sliced_run_)
  for (std::ptrdiff_t c = 0; c < count; ++c) enter(problem, static_cast<std::size_t>(c), r, m);
}

double NncgSolver::take_change(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                               const std::vector<Eigen::Vector3d>& m) {
  return over_support<false>([&](std::size_t c, double& squared) {
    d_[c] = r[c] - start_[c];
    squared += d_[c].squaredNorm();
    if (problem.rolling) {
      d_m_[c] = m[c] - start_m_[c];
      // Divided by R_eff, in N s, as the stop test adds them (GaussSeidelUpdate.h).
      if (problem.w_r[c] > 0.0)
        squared += d_m_[c].squaredNorm() / (problem.rolling_radius[c] * problem.rolling_radius[c]);
    }
  });
}

void NncgSolver::conjugate_step(const ContactProblem& problem, double beta,
                                std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& m,
                                std::vector<Eigen::Vector3d>& velocity,
                                std::vector<Eigen::Vector3d>& angular_velocity) {
  over_support<true>([&](std::size_t c, double&) {
    if (beta > 0.0 && !is_zero(p_[c])) {
      const Eigen::Vector3d step = beta * p_[c];
      r[c] += step;
      apply_impulse(problem, c, step, velocity, angular_velocity);
    }
    p_[c] = d_[c] + beta * p_[c];
    start_[c] = r[c];
    if (!problem.rolling) return;
    if (beta > 0.0 && !is_zero(p_m_[c])) {
      const Eigen::Vector3d step = beta * p_m_[c];
      m[c] += step;
      apply_rolling_impulse(problem, c, step, angular_velocity);
    }
    p_m_[c] = d_m_[c] + beta * p_m_[c];
    start_m_[c] = m[c];
  });
}

void NncgSolver::restart(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                         const std::vector<Eigen::Vector3d>& m) {
  over_support<false>([&](std::size_t c, double&) {
    p_[c].setZero();
    start_[c] = r[c];
    if (!problem.rolling) return;
    p_m_[c].setZero();
    start_m_[c] = m[c];
  });
}

SolveReport NncgSolver::solve_with_rolling(const ContactProblem& given,
                                           std::vector<Eigen::Vector3d>& given_r,
                                           std::vector<Eigen::Vector3d>& given_m,
                                           std::vector<Eigen::Vector3d>& velocity,
                                           std::vector<Eigen::Vector3d>& angular_velocity) {
  const bool coloured = options_.coloured;
  const bool parallel = coloured && static_cast<std::ptrdiff_t>(given.size()) >= settings_.parallel_from;
  if (coloured) ordered_.load(given, given_r, given_m, parallel);
  const bool sliced = !coloured && slabs_.update_if_large(given, options_.slabs, settings_.parallel_from);
  // In slab order the slabs are contiguous: each thread streams through its slab's contacts
  // (visited through the order instead, 44% more time per sweep on a 10^4 pour's first steps).
  if (sliced) sliced_.load(given, slabs_.order(), given_r, given_m, true);
  const ContactProblem& problem = coloured ? ordered_.problem() : sliced ? sliced_.problem() : given;
  std::vector<Eigen::Vector3d>& r = coloured ? ordered_.r() : sliced ? sliced_.r() : given_r;
  std::vector<Eigen::Vector3d>& m = coloured ? ordered_.m() : sliced ? sliced_.m() : given_m;
  const std::size_t count = problem.size();
  // assign() keeps the capacity: no allocation once the vectors have seen the largest problem.
  start_.assign(r.begin(), r.end());
  d_.assign(count, Eigen::Vector3d::Zero());
  p_.assign(count, Eigen::Vector3d::Zero());
  if (problem.rolling) {
    start_m_.assign(m.begin(), m.end());
    d_m_.assign(count, Eigen::Vector3d::Zero());
    p_m_.assign(count, Eigen::Vector3d::Zero());
  }
  in_support_.assign(count, 0);
  support_.clear();
  sliced_run_ = sliced;
  sweep_.forget_slab_lists();  // another problem
  scan_support(problem, r, m);
  steps_ = damped_ = drifted_ = restarts_ = 0;
  subspace_.start_solve();
  // The sweeps (GaussSeidelSweep.h) put each visited contact that carries a reaction into the
  // support and, after each backward sweep, take the conjugate step. Coloured and slab sweeps
  // visit from several threads, so the support is then brought up to date after the pair.
  struct Hooks : GaussSeidelSweepHooks {
    NncgSolver& solver;
    // Coloured, the support by a scan after each pair (enter() appends to support_, which
    // threads may not share). Sliced, each visit flags its own contact's slot (enter() writes
    // nothing else), so the threads keep it up to date as they sweep: a scan of every candidate
    // after each pair cost 9% of pour_3d's time (perf, 1 thread).
    bool scan = false;
    double previous = 0.0;  // |d|^2 of the last sweep pair; 0: no direction yet
    int max_sweeps = 0;     // of the current run of sweeps: its last is never followed by a step
    // Honest convergence's later runs (below): Siconos' residual (q_norm: ||q||) every
    // Options::siconos_check_every sweeps, the run ending as soon as it is within the tolerance.
    bool check_siconos = false;
    // Before that (the first run and its stall restarts): every Options::
    // siconos_check_unmet_every sweeps (0: never), q_norm computed at the first check.
    int unmet_every = 0;
    mutable double q_norm = -1.0;  // < 0: not computed yet

    bool converged_after_sweep(const GaussSeidelSweepState& state, const SolveReport& report) const {
      const int every = check_siconos ? solver.options_.siconos_check_every : unmet_every;
      if (every <= 0 || report.sweeps % every != 0) return false;
      if (q_norm < 0.0) q_norm = free_velocity_norm(state.problem);
      return siconos_residual(state.problem, state.r, state.m, state.velocity, state.angular_velocity, q_norm) <=
             solver.settings_.tolerance;
    }

    void after_visit(const GaussSeidelSweepState& state, std::size_t c) {
      if (!scan) solver.enter(state.problem, c, state.r, state.m);
    }
    bool stays_active(const GaussSeidelSweepState&, std::size_t c) const { return solver.in_support_[c] != 0; }
    // A symmetric pair (forward, backward) is one application of the map the conjugate
    // directions are built on. The solve only stops before a step (GaussSeidelSweep stops
    // right after a sweep), so it returns a sweep's reactions.
    void after_sweep(const GaussSeidelSweepState& state, const SolveReport& report, bool forward) {
      if (forward || report.sweeps >= max_sweeps) return;
      // A contact that opened and closed again within the pair has d = 0: a scan at the pair's
      // end misses nothing.
      if (scan) solver.scan_support(state.problem, state.r, state.m);
      // The subspace step changes only contacts with r_n > 0, all in the support already.
      if (solver.options_.subspace &&
          solver.subspace_.after_pair(state.problem, state.r, state.velocity, state.angular_velocity)) {
        solver.restart(state.problem, state.r, state.m);
        previous = 0.0;
        return;
      }
      const double current = solver.take_change(state.problem, state.r, state.m);
      double beta = previous > 0.0 ? current / previous : 0.0;
      if (beta > 1.0 && beta <= solver.options_.drift_ratio) {
        beta = 1.0;  // a drift (NncgSolver.h): followed with the whole step
        ++solver.drifted_;
      } else if (beta > 1.0) {
        // The pair's change grew. The paper restarts (beta = 0); in the collapse of a poured
        // bed that happens after every other pair and keeps only a 1.7x gain over "nlgs",
        // while keeping the direction with a damped beta converges in 4.9x fewer sweeps
        // (measured in development).
        beta = kBetaAfterGrowth;
        ++solver.damped_;
      }
      if (beta > 0.0) ++solver.steps_;
      solver.conjugate_step(state.problem, beta, state.r, state.m, state.velocity, state.angular_velocity);
      previous = current;
    }
  } hooks{{}, *this, coloured};
  GaussSeidelSweep::Options options;
  // Active-set sweeps in sliced solves only (Options::full_sweep_every): small problems keep
  // every sweep full.
  options.full_sweep_every = sliced ? options_.full_sweep_every : 1;
  options.stall_sweeps = stall_window();
  if (coloured) {
    options.colour_start = &ordered_.colour_start();
    options.parallel = parallel;
  }
  if (sliced) {
    options.slabs = &slabs_;
    options.parallel = true;
  }
  const GaussSeidelSweepState state{problem, r, m, velocity, angular_velocity};
  if (settings_.siconos_stop)
    hooks.unmet_every = settings_.residual_check_every >= 0 ? settings_.residual_check_every
                                                             : options_.siconos_check_unmet_every;
  auto run = [&](const SolverSettings& settings) {
    hooks.max_sweeps = settings.max_iterations;
    return coloured ? sweep_.solve<GaussSeidelSweep::Order::colour>(settings, options, state, hooks)
           : sliced ? sweep_.solve<GaussSeidelSweep::Order::slab>(settings, options, state, hooks)
                    : sweep_.solve<GaussSeidelSweep::Order::index>(settings, options, state, hooks);
  };
  SolveReport report = run(settings_);
  // A stall (Options::stall_restarts): the direction the pairs built has stopped helping; the
  // sweeps start again from the stalled reactions with none, with what is left of the budget.
  for (; restarts_ < options_.stall_restarts && report.stalled &&
         report.sweeps < settings_.max_iterations;
       ++restarts_) {
    restart(problem, r, m);
    hooks.previous = 0.0;
    SolverSettings rest = settings_;
    rest.max_iterations = settings_.max_iterations - report.sweeps;
    SolveReport more = run(rest);
    more.sweeps += report.sweeps;
    report = more;
  }
  // Honest convergence (SolverSettings::siconos_stop): the sweep test understates how far a
  // slowly contracting solve is from the law (error ~ change / (1 - rate)), so a converged run
  // goes on with the sweep test tightened by the factor it missed by (halved), from the
  // reactions it reached, until Siconos' residual is within the tolerance too.
  if (settings_.siconos_stop && report.converged) {
    const double q_norm = hooks.q_norm >= 0.0 ? hooks.q_norm : free_velocity_norm(problem);  // the checks' when they ran
    double sweep_tolerance = settings_.tolerance;
    hooks.check_siconos = true;
    hooks.q_norm = q_norm;
    constexpr int kRounds = 40;  // runs of sweeps at most; each tightens by at least 2x
    for (int round = 0; round < kRounds && report.converged; ++round) {
      const double e = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
      if (e <= settings_.tolerance) break;
      if (report.sweeps >= settings_.max_iterations) {
        report.converged = false;
        break;
      }
      sweep_tolerance *= std::max(1e-3, 0.5 * settings_.tolerance / e);
      if (!(sweep_tolerance > 0.0)) break;  // tightened to nothing: the budget decides
      restart(problem, r, m);
      hooks.previous = 0.0;
      SolverSettings rest = settings_;
      rest.tolerance = sweep_tolerance;
      rest.max_iterations = settings_.max_iterations - report.sweeps;
      SolveReport more = run(rest);
      more.sweeps += report.sweeps;
      report = more;
      if (report.converged && round == kRounds - 1)
        report.converged = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm) <= settings_.tolerance;
    }
  }
  if (coloured) ordered_.store(given_r, given_m, parallel);
  if (sliced) sliced_.store(given_r, given_m, true);
  return report;
}

}  // namespace tmdem::mechanics
