#pragma once
// The contacts cut into slabs across one axis, for a Gauss-Seidel sweep that threads share
// with few barriers ("nlgs" and "nncg" from SolverSettings::parallel_from contacts).
//
// A contact sits at the midpoint of its two particles (a wall contact: at its particle) along
// problem.split_axis. Two contacts that share a particle are then at most `span` apart, span
// being the largest distance along the axis between the two particles of a contact; slabs at
// least that wide put two such contacts in the same or in neighbouring slabs. So the even
// slabs touch disjoint particles, and so do the odd ones: a sweep visits phase 0 (the even
// slabs, several at once, each in index order by one thread), then phase 1 (the odd slabs),
// then phase 2 (a piston's contacts, which all share its body, and the long candidates: one
// slab, one thread). Two barriers per sweep where the greedy colouring of "nlgs_coloured"
// needs one per colour (about 30 in a 3D bed), and inside each slab the sweep keeps the
// problem's own order, so a load still crosses the whole height of a slab in one sweep.
//
// The long candidates: look-ahead pairs further apart along the axis than any two touching
// particles (the sum of their radii), which only fast particles have. They go to the last
// phase, so that the span, and the slabs' width, is that of touching pairs: pour_3d's falling
// spheres had widened its 19 mm into 3 slabs, whose odd phase of one slab left a second thread
// idle. The slabs are cut to about equal work (closed contacts weigh 4: the partial sweeps
// visit them too), each at least `span` wide, and their count is a multiple of 4 from 4 on,
// so that each phase holds an even number for two threads to share.
//
// A periodic split axis (problem.split_period): a contact sits at the midpoint of its nearest
// image, wrapped into the period, the slabs fill the period and go round it, their count even
// (slab 0 and the last are neighbours and must fall in different phases) and at least 4.
//
// The cut depends only on the problem (positions, pairs, axis) and `slabs`, never on the
// thread count: every thread count sweeps in the same order and gives the same bits.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

class ContactSlabs {
 public:
  static constexpr int kPhases = 3;  // even slabs, odd slabs, a piston's and the long contacts
  // How many slabs "nlgs" and "nncg" ask for: 4 a phase, enough for 2 to 4 threads, and as
  // wide as the bed allows, so that a force chain has few slab boundaries to cross (a sweep
  // carries it into the next slab once a phase). The 2D pours of bench/beds were at rest on
  // three seeds with 8 (192-575 steps); with 16, seed 21 was not within 300 s (2 threads).
  static constexpr int kDefaultSlabs = 8;

  // Cuts problem's contacts into at most `slabs` slabs (fewer where the span allows fewer; a
  // multiple of 4 from 4 on). Returns false, and holds no cut, when problem gives no
  // positions, fewer than 3 slabs fit (no two slabs of one phase to share out), or more than
  // half its contacts would go to the last phase.
  bool update(const ContactProblem& problem, int slabs);
  // The slab decision of "nlgs" and "nncg": cut (update) only a problem of at least
  // parallel_from contacts, into about `slabs` (0: never). Whether it was cut; when not, the
  // sweeps keep the problem's order and the last cut is left as it was.
  bool update_if_large(const ContactProblem& problem, int slabs, std::ptrdiff_t parallel_from) {
    return slabs > 0 && static_cast<std::ptrdiff_t>(problem.size()) >= parallel_from &&
           update(problem, slabs);
  }

  bool valid() const { return !slab_start_.empty(); }
  std::size_t slab_count() const { return slab_start_.empty() ? 0 : slab_start_.size() - 1; }
  // Slab s holds contacts order()[slab_start()[s], slab_start()[s + 1]), in increasing index;
  // phase p is slabs [phase_start()[p], phase_start()[p + 1]).
  const std::vector<std::int32_t>& order() const { return order_; }
  const std::vector<std::int32_t>& slab_start() const { return slab_start_; }
  const std::vector<std::int32_t>& phase_start() const { return phase_start_; }

 private:
  static constexpr std::size_t kBins = 64;  // histogram bins a slab (cut_boundaries)
  static std::int64_t visit_weight(const ContactProblem& problem, std::size_t c);
  // boundary_: cut + 1 edges from low to high, slabs of about equal work, each >= min_width.
  void cut_boundaries(const ContactProblem& problem, double low, double high, double min_width,
                      std::int32_t cut);
  std::int32_t slab_at(double x) const;  // the slab (left to right) holding x

  std::vector<std::int64_t> work_;
  std::vector<double> boundary_;
  std::vector<double> midpoint_;  // per contact of a slab: midpoint() along the axis, m
  std::vector<std::int32_t> slab_of_;  // per contact: its slab in visiting order
  std::vector<std::int32_t> order_, slab_start_, phase_start_, cursor_;
};

}  // namespace tmdem::mechanics
