#pragma once
// Active-set sweeps of the Gauss-Seidel solvers ("nlgs", "nlgs_coloured", and "nncg" in its
// sliced solves): which contacts a sweep visits.
//
// Look-ahead detection hands the solver every pair that might touch within the step
// (NscdIntegrator::refresh_candidates); most of them stay open (pouring 2,000 spheres: 20k-68k
// candidates for 1k-4.3k contacts). A candidate is *passive* when its last visit left it at
// r_c = 0 (and m_c = 0): its local solve found it separating, u_n >= 0 with every other
// reaction frozen. Visiting it again changes nothing until another contact's impulse turns
// its u_n negative, so most sweeps ("partial") visit the active contacts only, and a *full*
// sweep over every candidate runs
//   - first (the warm start says nothing about which candidates are open),
//   - every full_sweep_every sweeps (SolverSettings; a partial sweep cannot see a passive
//     candidate closing, a full one makes it active again),
//   - after any partial sweep that met the tolerance, and as the last allowed sweep.
// Convergence and stall are judged on full sweeps only (GaussSeidelStopTest), so a converged
// answer passed exactly the test every candidate passes without active sets: a full sweep
// whose change / total <= tolerance.
//
// The fixed point does not change: a partial sweep is a Gauss-Seidel sweep of the same
// problem with the passive reactions held at 0, and a passive candidate's own visit would
// have left it at 0 as long as it stays open. Skipping it only delays a candidate that is
// closing to the next full sweep; the answer the stop test accepts is a fixed point of every
// candidate's local law (to the tolerance), as before. The path to it differs (another
// order of visits), so iterates differ from full sweeps by round-off and by the delay.
//
// The passive marks are written per contact during a full sweep (distinct bytes: contacts of
// one colour may be marked by different threads) and the active list is collected after it
// in index order, segment by segment (one segment per colour for "nlgs_coloured"), so it does
// not depend on the thread count. No allocation once warm: the vectors keep their capacity.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tmdem::mechanics {

class ActiveContactSet {
 public:
  // A new solve of `count` contacts, at most max_sweeps sweeps, a full sweep at least every
  // full_sweep_every sweeps (1: every sweep is full, the plain Gauss-Seidel).
  void start(std::size_t count, int full_sweep_every, int max_sweeps) {
    every_ = full_sweep_every < 1 ? 1 : full_sweep_every;
    if (partial_sweeps()) passive_.assign(count, 1);
    max_sweeps_ = max_sweeps;
    since_full_ = 0;
    full_next_ = true;
    full_sweeps_ = 0;
  }

  // Whether any sweep can be partial (full_sweep_every > 1). Otherwise every sweep is full
  // and nothing reads the passive marks or the active list: the solvers skip marking and
  // collecting (mark_* and collect), whose per-candidate branch on the 2,000 pour bed at rest
  // was a third of a sweep's mispredicted branches (measured in development).
  bool partial_sweeps() const { return every_ > 1; }

  // Whether sweep number `sweep` (1, 2, ...) visits every contact.
  bool full(int sweep) const { return full_next_ || sweep >= max_sweeps_; }

  // During a full sweep, when partial_sweeps(): contact c is not solvable (never visited).
  void mark_unsolvable(std::size_t c) { passive_[c] = 1; }
  // During a full sweep, when partial_sweeps(): contact c's visit left it with `total` (|r_c| + |m_c| / R_eff, 0
  // exactly when it left r_c = 0 and m_c = 0: open).
  void mark_visited(std::size_t c, double total) { passive_[c] = total == 0.0 ? 1 : 0; }

  // After a full sweep, when partial_sweeps(): the active contacts of [segment_start[k], segment_start[k + 1]) for
  // each k, in increasing order, are active()[active_start()[k], active_start()[k + 1]).
  void collect(const std::vector<std::int32_t>& segment_start) {
    active_.clear();
    active_start_.clear();
    active_start_.push_back(0);
    for (std::size_t k = 0; k + 1 < segment_start.size(); ++k) {
      for (std::int32_t c = segment_start[k]; c < segment_start[k + 1]; ++c) {
        if (!passive_[static_cast<std::size_t>(c)]) active_.push_back(c);
      }
      active_start_.push_back(static_cast<std::int32_t>(active_.size()));
    }
  }
  // The same for one segment, all `count` contacts.
  void collect(std::size_t count) {
    one_segment_.assign({0, static_cast<std::int32_t>(count)});
    collect(one_segment_);
  }

  // After each sweep: whether it was full and met the tolerance (change <= tolerance total).
  void after_sweep(bool was_full, bool tolerance_met) {
    if (was_full) {
      since_full_ = 0;
      ++full_sweeps_;
    } else {
      ++since_full_;
    }
    // A partial sweep that met the tolerance must be confirmed by a full one.
    full_next_ = (!was_full && tolerance_met) || since_full_ + 1 >= every_;
  }

  // Whether the last full sweep left contact c passive.
  bool passive(std::size_t c) const { return passive_[c] != 0; }
  const std::vector<std::int32_t>& active() const { return active_; }
  const std::vector<std::int32_t>& active_start() const { return active_start_; }
  int full_sweeps() const { return full_sweeps_; }

 private:
  std::vector<std::uint8_t> passive_;  // per contact, from the last full sweep
  std::vector<std::int32_t> active_, active_start_, one_segment_;
  int every_ = 1, max_sweeps_ = 0, since_full_ = 0, full_sweeps_ = 0;
  bool full_next_ = true;
};

}  // namespace tmdem::mechanics
