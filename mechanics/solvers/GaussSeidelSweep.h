#pragma once
// The sweep loop of every Gauss-Seidel solver, written once: "nlgs" (GaussSeidelSolver.h),
// "nlgs_coloured" (ColouredGaussSeidelSolver.h), "nlgs_block" (BlockGaussSeidelSolver.h) and
// "nncg" (NncgSolver.h, these sweeps plus its conjugate step). A solve starts from
// v = v_free + M^-1 H r, then sweeps single visits (gauss_seidel_visit, GaussSeidelUpdate.h)
// until GaussSeidelStopTest ends it or max_iterations sweeps have run. Options:
//   - the visiting order (Order, a template argument: each solver compiles its own loop, with
//     the visit inlined in it): odd sweeps go forwards and even sweeps backwards in every
//     order (symmetric: a load travels the whole length of a chain in one pair of sweeps,
//     whichever way the contacts happen to be numbered);
//       index       the contacts in index order;
//       colour      colour by colour (ContactColouring.h); the contacts of one colour share no
//                   body, so each colour is one OpenMP loop, and the sweep's sums add fixed
//                   blocks of visit slots (FixedBlockSums.h): the same bits for any thread count;
//       slab        slab by slab (ContactSlabs.h; the problem in slab order, so that slab s
//                   is contacts [slab_start[s], slab_start[s + 1])): the slabs of one phase
//                   touch disjoint particles, so each phase is one OpenMP loop over its slabs,
//                   each slab visited in index order by one thread; the sweep's sums add per-slab sums in
//                   slab order: the same bits for any thread count (full sweeps only);
//       body_block  index order, except that a contact owned by a body block hands its whole
//                   block to the solver (Hooks::visit_block) at the first of the block's
//                   contacts a sweep reaches, once per sweep;
//   - the active set (ActiveContactSet.h): full_sweep_every > 1 lets most sweeps visit the
//     active contacts only (index, colour and slab orders; in slab order each slab's thread
//     collects the slab's active list at the end of its part of a full sweep, so the lists
//     do not depend on the thread count). Hooks::stays_active keeps a contact active that
//     its visit left open.
// The solver's own steps are hooks called from the loop (static, no virtual call per contact;
// GaussSeidelSweepHooks lists them). Sums: index and body_block orders add each visit's change
// and total in visiting order; colour order as above. No allocation once warm.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/model/StepInterrupt.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ActiveContactSet.h"
#include "mechanics/solvers/ContactSlabs.h"
#include "mechanics/solvers/ContactSolver.h"
#include "mechanics/solvers/FixedBlockSums.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"

namespace tmdem::mechanics {

// What a solve works on: the problem, its reactions r (N s, local) and rolling impulses m
// (N m s; read only when problem.rolling) and the body velocities they give.
struct GaussSeidelSweepState {
  const ContactProblem& problem;
  std::vector<Eigen::Vector3d>& r;
  std::vector<Eigen::Vector3d>& m;
  std::vector<Eigen::Vector3d>& velocity;
  std::vector<Eigen::Vector3d>& angular_velocity;
};

// The solver's steps inside the loop; a solver derives from this and hides what it needs.
struct GaussSeidelSweepHooks {
  // After the single visit of solvable contact c (colour order: from several threads at once,
  // each with its own c).
  void after_visit(const GaussSeidelSweepState& /*state*/, std::size_t /*c*/) {}
  // Active sets: whether contact c stays active although its last visit left it open (nncg:
  // a contact of its support, whose conjugate steps may move a reaction it left at zero).
  bool stays_active(const GaussSeidelSweepState& /*state*/, std::size_t /*c*/) const { return false; }
  // body_block order: the visit of block b, `forward` as the sweep goes. single(c) visits
  // contact c alone and adds it to `sums`, the sweep's running change and total (N s).
  template <class Single>
  void visit_block(const GaussSeidelSweepState& /*state*/, std::size_t /*b*/, bool /*forward*/,
                   ContactUpdate& /*sums*/, Single&& /*single*/) {}
  // After a sweep the stop test let pass: whether the solver's own measure ends the solve
  // here, converged (nncg: Siconos' residual within the tolerance, NncgSolver::Options::
  // siconos_check_every).
  bool converged_after_sweep(const GaussSeidelSweepState& /*state*/, const SolveReport& /*report*/) {
    return false;
  }
  // After a sweep the stop test let pass (report.sweeps: its number).
  void after_sweep(const GaussSeidelSweepState& /*state*/, const SolveReport& /*report*/,
                   bool /*forward*/) {}
};

class GaussSeidelSweep {
 public:
  enum class Order { index, colour, slab, body_block };
  struct Options {
    int full_sweep_every = 1;  // ActiveContactSet::start; 1: every sweep visits every contact
    int stall_sweeps = 500;    // GaussSeidelStopTest's stall window, sweeps
    // colour: contacts [colour_start[k], colour_start[k + 1]) have colour k; `parallel`: OpenMP
    // threads inside each colour.
    const std::vector<std::int32_t>* colour_start = nullptr;
    bool parallel = false;
    // slab: the cut, the problem in its order (parallel: OpenMP threads share each phase's slabs).
    const ContactSlabs* slabs = nullptr;
    // body_block: per contact its block (< block_count), -1 for a single visit.
    const std::vector<std::int32_t>* block_of = nullptr;
    std::size_t block_count = 0;
  };

  template <Order order, class Hooks>
  SolveReport solve(const SolverSettings& settings, const Options& options,
                    const GaussSeidelSweepState& state, Hooks& hooks);
  // Of the last solve: the sweeps that visited every candidate (with active sets, the others
  // visited the active contacts only).
  int full_sweeps() const { return active_.full_sweeps(); }

  // Slab order with active sets: slab s's active contacts of the last full sweep, in increasing
  // order, are slab_active()[slab_start[s], slab_active_end()[s]) (ContactSlabs::slab_start).
  // Every contact a sweep since then visited is among them (partial sweeps visit no other), and
  // so is every contact that carried a reaction in that sweep (Hooks::stays_active). Valid from
  // the first full sweep of a solve that marks (active sets on) until forget_slab_lists() (the
  // next problem) or a run without active sets.
  bool slab_lists_valid() const { return slab_lists_valid_; }
  const std::vector<std::int32_t>& slab_active() const { return slab_active_; }
  const std::vector<std::int32_t>& slab_active_end() const { return slab_active_end_; }
  void forget_slab_lists() { slab_lists_valid_ = false; }

 private:
  // One sweep in index order (Blocks: body_block order); returns its change and total.
  template <bool Blocks, class Hooks>
  ContactUpdate sweep_index(const Options& options, double relaxation, int sweep, bool forward,
                            bool full, bool mark, const GaussSeidelSweepState& state, Hooks& hooks);
  template <class Hooks>
  ContactUpdate sweep_colours(const Options& options, double relaxation, bool forward, bool full,
                              bool mark, const GaussSeidelSweepState& state, Hooks& hooks);

  template <class Hooks>
  ContactUpdate sweep_slabs(const Options& options, double relaxation, bool forward, bool full,
                            bool mark, const GaussSeidelSweepState& state, Hooks& hooks);

  // A full sweep's mark: contact c is active when its visit left it carrying `total`, or when
  // the solver keeps it active (Hooks::stays_active: nncg's support).
  template <class Hooks>
  void mark_visited(const GaussSeidelSweepState& state, Hooks& hooks, std::size_t c, double total) {
    active_.mark_visited(c, hooks.stays_active(state, c) ? 1.0 : total);
  }

  ActiveContactSet active_;             // the contacts partial sweeps visit
  std::vector<double> change_, total_;  // colour order: per visit slot, this sweep, N s
  std::vector<double> block_sums_;      // colour order: per block of slots: change, total
  std::vector<double> slab_sums_;       // slab order: per slab: change, total
  // slab order with active sets: slab s's active contacts, in increasing order, are
  // slab_active_[slab_start[s], slab_active_end_[s]) (each slab's thread collects its own).
  std::vector<std::int32_t> slab_active_, slab_active_end_;
  bool slab_lists_valid_ = false;
  std::vector<std::int32_t> slab_order_;  // per phase, its slabs from the most contacts to visit down
  std::vector<int> visited_;            // body_block order: per block, the sweep that last visited it
};

template <GaussSeidelSweep::Order order, class Hooks>
SolveReport GaussSeidelSweep::solve(const SolverSettings& settings, const Options& options,
                                    const GaussSeidelSweepState& state, Hooks& hooks) {
  state.problem.velocities_from_reactions(state.r, state.m, state.velocity, state.angular_velocity);
  const std::size_t count = state.problem.size();
  if constexpr (order == Order::colour) {
    change_.resize(count);
    total_.resize(count);
    block_sums_.resize(static_cast<std::size_t>(2 * sum_block_count(static_cast<std::ptrdiff_t>(count))));
  } else if constexpr (order == Order::slab) {
    slab_sums_.resize(2 * options.slabs->slab_count() + 2);
    if (options.full_sweep_every > 1) {
      slab_active_.resize(count);
      slab_active_end_.resize(options.slabs->slab_count());
    }
  } else if constexpr (order == Order::body_block) {
    visited_.assign(options.block_count, 0);
  }
  SolveReport report;
  GaussSeidelStopTest stop(settings.tolerance, options.stall_sweeps);
  active_.start(count, options.full_sweep_every, settings.max_iterations);
  // A run whose full sweeps do not mark may visit contacts the lists do not hold.
  if (!active_.partial_sweeps()) slab_lists_valid_ = false;
  while (report.sweeps < settings.max_iterations) {
    ++report.sweeps;
    const bool forward = report.sweeps % 2 == 1;
    // Full sweeps visit every contact and mark the passive ones, partial sweeps the active
    // ones only, in the same relative order (ActiveContactSet.h).
    const bool full = active_.full(report.sweeps);
    const bool mark = full && active_.partial_sweeps();  // else nothing reads the marks
    ContactUpdate sums;
    if constexpr (order == Order::colour) {
      sums = sweep_colours(options, settings.relaxation, forward, full, mark, state, hooks);
    } else if constexpr (order == Order::slab) {
      sums = sweep_slabs(options, settings.relaxation, forward, full, mark, state, hooks);
    } else {
      sums = sweep_index<order == Order::body_block>(options, settings.relaxation, report.sweeps,
                                                      forward, full, mark, state, hooks);
    }
    if constexpr (order == Order::slab) slab_lists_valid_ = slab_lists_valid_ || mark;  // marked in the sweep
    if (stop.after_sweep(sums.change, sums.total, report, full)) break;
    if (step_interrupt_requested()) break;  // the step is given up (StepInterrupt.h)
    if (hooks.converged_after_sweep(state, report)) {
      report.converged = true;
      break;
    }
    if (mark) {
      if constexpr (order == Order::colour) {
        active_.collect(*options.colour_start);
      } else if constexpr (order == Order::slab) {
        // collected slab by slab in the sweep
      } else {
        active_.collect(count);
      }
    }
    active_.after_sweep(full, stop.met());
    hooks.after_sweep(state, report, forward);
  }
  return report;
}

template <bool Blocks, class Hooks>
ContactUpdate GaussSeidelSweep::sweep_index(const Options& options, double relaxation, int sweep,
                                            bool forward, bool full, bool mark,
                                            const GaussSeidelSweepState& state, Hooks& hooks) {
  const ContactProblem& problem = state.problem;
  std::vector<Eigen::Vector3d>& r = state.r;
  std::vector<Eigen::Vector3d>& m = state.m;
  std::vector<Eigen::Vector3d>& velocity = state.velocity;
  std::vector<Eigen::Vector3d>& angular_velocity = state.angular_velocity;
  ContactUpdate sums;
  auto single = [&](std::size_t c) {
    const ContactUpdate u = gauss_seidel_visit(problem, c, relaxation, r[c], m, velocity, angular_velocity);
    sums.change += u.change;
    sums.total += u.total;
    return u;
  };
  const std::vector<std::int32_t>& active = active_.active();
  const std::size_t visits = full ? problem.size() : active.size();
  for (std::size_t visit = 0; visit < visits; ++visit) {
    const std::size_t k = forward ? visit : visits - 1 - visit;
    const std::size_t c = full ? k : static_cast<std::size_t>(active[k]);
    if (!problem.solvable(c)) {
      if (mark) active_.mark_unsolvable(c);
      continue;
    }
    if constexpr (Blocks) {
      if (const std::int32_t b = (*options.block_of)[c]; b >= 0) {
        if (visited_[b] == sweep) continue;
        visited_[b] = sweep;
        hooks.visit_block(state, static_cast<std::size_t>(b), forward, sums, single);
        continue;
      }
    }
    const ContactUpdate u = single(c);
    if (mark) mark_visited(state, hooks, c, u.total);
    hooks.after_visit(state, c);
  }
  return sums;
}

template <class Hooks>
ContactUpdate GaussSeidelSweep::sweep_colours(const Options& options, double relaxation, bool forward,
                                              bool full, bool mark, const GaussSeidelSweepState& state,
                                              Hooks& hooks) {
  const ContactProblem& problem = state.problem;
  std::vector<Eigen::Vector3d>& r = state.r;
  std::vector<Eigen::Vector3d>& m = state.m;
  std::vector<Eigen::Vector3d>& velocity = state.velocity;
  std::vector<Eigen::Vector3d>& angular_velocity = state.angular_velocity;
  const std::vector<std::int32_t>& start = *options.colour_start;
  const auto colours = static_cast<std::ptrdiff_t>(start.size()) - 1;
  const std::vector<std::int32_t>& active = active_.active();
  // Visit slots: contact q in a full sweep, active()[q] in a partial one.
  const std::vector<std::int32_t>& slot_start = full ? start : active_.active_start();
  const std::ptrdiff_t slots = slot_start[static_cast<std::size_t>(colours)];
  const std::ptrdiff_t slot_blocks = sum_block_count(slots);
#pragma omp parallel if (options.parallel)
  {
    for (std::ptrdiff_t visit = 0; visit < colours; ++visit) {
      const std::ptrdiff_t k = forward ? visit : colours - 1 - visit;
#pragma omp for schedule(static)
      for (std::ptrdiff_t q = slot_start[k]; q < slot_start[k + 1]; ++q) {
        const auto c = static_cast<std::size_t>(full ? q : active[q]);
        ContactUpdate u;
        if (problem.solvable(c)) {
          u = gauss_seidel_visit(problem, c, relaxation, r[c], m, velocity, angular_velocity);
          if (mark) mark_visited(state, hooks, c, u.total);
          hooks.after_visit(state, c);
        } else if (mark) {
          active_.mark_unsolvable(c);
        }
        change_[q] = u.change;
        total_[q] = u.total;
      }
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t block = 0; block < slot_blocks; ++block) {
      double change = 0.0, total = 0.0;
      for (std::ptrdiff_t q = block * kSumBlock; q < std::min(slots, (block + 1) * kSumBlock); ++q) {
        change += change_[q];
        total += total_[q];
      }
      block_sums_[2 * block] = change;
      block_sums_[2 * block + 1] = total;
    }
  }
  const auto [change, total] = add_block_sums<2>(block_sums_, slot_blocks);
  return {change, total};
}

template <class Hooks>
ContactUpdate GaussSeidelSweep::sweep_slabs(const Options& options, double relaxation, bool forward,
                                            bool full, bool mark, const GaussSeidelSweepState& state,
                                            Hooks& hooks) {
  const ContactSlabs& slabs = *options.slabs;
  const std::vector<std::int32_t>& start = slabs.slab_start();
  const std::vector<std::int32_t>& phase = slabs.phase_start();
  // Slabs differ in size, and in a partial sweep in their active contacts: threads take them one
  // at a time, largest first (which thread sweeps a slab, and when, changes nothing in the
  // result: the slabs of a phase touch disjoint particles and their sums are added in slab order).
  slab_order_.resize(slabs.slab_count());
  for (int p = 0; p < ContactSlabs::kPhases; ++p) {
    for (std::int32_t s = phase[p]; s < phase[p + 1]; ++s) slab_order_[static_cast<std::size_t>(s)] = s;
    const auto cost = [&](std::int32_t s) {
      return (full ? start[s + 1] : slab_active_end_[static_cast<std::size_t>(s)]) - start[s];
    };
    std::stable_sort(slab_order_.begin() + phase[p], slab_order_.begin() + phase[p + 1],
                     [&](std::int32_t a, std::int32_t b) { return cost(a) > cost(b); });
  }
#pragma omp parallel if (options.parallel)
  for (int visit = 0; visit < ContactSlabs::kPhases; ++visit) {
    const int p = forward ? visit : ContactSlabs::kPhases - 1 - visit;
    if (phase[p] == phase[p + 1]) continue;  // no piston: no barrier for its empty phase
#pragma omp for schedule(dynamic, 1)
    for (std::int32_t i = phase[p]; i < phase[p + 1]; ++i) {
      const std::int32_t s = slab_order_[static_cast<std::size_t>(i)];
      double change = 0.0, total = 0.0;
      const std::int32_t first = start[s];
      // A partial sweep visits the slab's active list, a full one the whole slab.
      const std::int32_t end = full ? start[s + 1] : slab_active_end_[static_cast<std::size_t>(s)];
      for (std::int32_t k = 0; k < end - first; ++k) {
        const std::int32_t slot = forward ? first + k : end - 1 - k;
        const auto c = static_cast<std::size_t>(full ? slot : slab_active_[static_cast<std::size_t>(slot)]);
        if (!state.problem.solvable(c)) {
          if (mark) active_.mark_unsolvable(c);
          continue;
        }
        const ContactUpdate u = gauss_seidel_visit(state.problem, c, relaxation, state.r[c], state.m,
                                                   state.velocity, state.angular_velocity);
        change += u.change;
        total += u.total;
        hooks.after_visit(state, c);
        if (mark) mark_visited(state, hooks, c, u.total);
      }
      if (mark) {  // this slab's active contacts for the partial sweeps, in increasing order
        std::int32_t n = first;
        for (std::int32_t c = first; c < start[s + 1]; ++c)
          if (!active_.passive(static_cast<std::size_t>(c))) slab_active_[static_cast<std::size_t>(n++)] = c;
        slab_active_end_[static_cast<std::size_t>(s)] = n;
      }
      slab_sums_[2 * static_cast<std::size_t>(s)] = change;
      slab_sums_[2 * static_cast<std::size_t>(s) + 1] = total;
    }
  }
  ContactUpdate sums;
  for (std::size_t s = 0; s < slabs.slab_count(); ++s) {
    sums.change += slab_sums_[2 * s];
    sums.total += slab_sums_[2 * s + 1];
  }
  return sums;
}

}  // namespace tmdem::mechanics
