#pragma once
// Persistent table of candidate contacts (particle-particle and particle-wall), rebuilt from
// a cell grid only when some particle may have come close to a pair that is not listed.
//
// A pair is listed when its gap is at most `margin` at the rebuild. Between rebuilds each
// particle's displacement d_i since the rebuild is tracked; as long as
// d_i + s_i <= margin / 2 for every particle (s_i = look-ahead: how far it can move during
// the coming step), no unlisted pair can touch before the next check. This is the
// "half the margin" Verlet criterion, with a look-ahead so that fast particles trigger the
// rebuild one step early rather than one step late. A moving wall (a piston) is held to the
// same test with its own displacement and look-ahead against its own margin, the wall margin
// (at least the particles' margin, and 4 times the walls' largest look-ahead): a particle-wall
// gap then closes by at most margin / 2 + wall margin / 2 <= wall margin, and particle-wall
// pairs are listed within the wall margin. A fast piston so widens its own pairs only: with one
// margin for all, a piston falling at 7 m/s (periodic_pressed) had made every one of 1,000
// spheres a candidate of every other (500,500 pairs, 4 ms a sweep).
//
// Periodic axes (particles.box): the grid wraps, pairs and displacements are measured through
// the nearest image, and a pair across a boundary is the same (i, j) entry as inside the box,
// so wrapping a particle keeps its candidates and their warm starts. Only the nearest image is
// listed, so a second test holds the motion of every pair *along the periodic axes* (the two
// particles' displacements since the rebuild plus their look-aheads, along those axes) to the
// fitted margin, half the shortest period less 2 r_max: no second image can then come into
// reach. The two largest of the particles' sums decide it, so one sphere kicked sideways may
// use most of the margin alone. Motion along the other axes is held to the listing
// margin only: a piston landing at 8 m/s across a bed periodic in x and z (periodic_pressed,
// seed 12) kicks a sphere 4.1 mm a step along y (its look-ahead), more than half the 8 mm the
// 20 mm periods leave, and had stopped the run when every axis was held to the fitted margin. Below the
// fitted margin the second test is implied by the first: the tables are those of one test.
//
// Everything lives in reused vectors: no allocation once warm.
//
// Parallel (OpenMP, from parallel_from particles on): each thread lists the pairs (i, j > i)
// and walls of one contiguous range of particles i, already in table order, and the ranges
// are concatenated in order; the previous-table map is one binary search per pair. Every
// pair is decided by the same arithmetic whichever thread does it, so the table is the same
// bits for any thread count.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mechanics/model/ParallelFrom.h"
#include "mechanics/detection/CellGrid.h"
#include "mechanics/model/PairIndex.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/model/Wall.h"

namespace tmdem::mechanics {

struct CandidatePair {
  std::int32_t i = 0;  // particle
  std::int32_t j = 0;  // particle (> i), or wall_code(wall) (PairIndex.h)
};

class ContactDetector {
 public:
  // margin bounds, m: the margin used at a rebuild is 4 * (largest look-ahead) clamped to
  // (never below 2 * the largest look-ahead, so fast particles cannot tunnel)
  // [min_margin_m, max_margin_m] (wider when particles are fast, so rebuilds stay rare).
  // parallel_from: particles from which rebuilds and checks use OpenMP threads (0: always).
  ContactDetector(double min_margin_m, double max_margin_m, std::ptrdiff_t parallel_from = kDefaultParallelFrom);

  // Rebuilds the table if needed (or if forced). lookahead_m[i] is how far particle i may
  // move before the next call (may be empty: 0), wall_lookahead_m[w] the same for wall w (may
  // be empty: walls are fixed), periodic_lookahead_m[i] how far particle i may move along the
  // periodic axes (may be empty: lookahead_m). Returns true if the table was rebuilt. Throws
  // std::runtime_error when a periodic look-ahead is beyond what the periods allow.
  bool update(const ParticleSet& particles, const std::vector<Wall>& walls,
              const std::vector<double>& lookahead_m,
              const std::vector<double>& wall_lookahead_m = {},
              const std::vector<double>& periodic_lookahead_m = {});

  // Whether the two largest look-aheads along the periodic axes (m, per particle) fit together in
  // half the shortest period less 2 r_max, as update() needs (true without periodic axes). A
  // step that fails it is taken in parts (NscdIntegrator::step).
  bool fits_periods(const ParticleSet& particles, const std::vector<double>& periodic_lookahead_m) const;

  // The largest look-ahead (m) of a moving wall that can touch a particle within the coming step
  // (its gap to the particle within the two look-aheads): such a wall may hand its speed to the
  // bed, and update() lists the particles' pairs within its reach too. 0 when none can.
  double engaged_wall_lookahead(const ParticleSet& particles, const std::vector<Wall>& walls,
                                const std::vector<double>& lookahead_m,
                                const std::vector<double>& wall_lookahead_m) const;
  // Whether `wall` (look-ahead wall_lookahead_m, m) can touch a particle within the coming
  // step: a particle whose centre is on the wall's side, its gap within the two look-aheads.
  bool wall_engaged(const ParticleSet& particles, const Wall& wall, double wall_lookahead_m,
                    const std::vector<double>& lookahead_m) const;
  // Whether a wall's reach (m) is beyond half the widest margin the particles' own look-aheads
  // may ask (max_margin): listing the particles' pairs within it would take a wider table than
  // any particle does.
  bool wall_reach_exceeds_margin(double reach_m) const { return 2.0 * reach_m > max_margin_; }

  // Forces a rebuild at the next update (after particles were moved by hand).
  void invalidate() { valid_ = false; }

  // Whether the table still holds every pair that can touch once each particle has moved on by
  // travel_m[i] and each wall w by wall_travel_m[w] along its normal (m) from where they stand:
  // the tests of update() on the positions after that travel, with no look-ahead. A step's
  // actual travel, checked after its solve, where the table was listed with a reach that is an
  // estimate rather than a bound (NscdIntegrator: a piston the bed holds). False for a table
  // that is not valid.
  bool covers(const ParticleSet& particles, const std::vector<Eigen::Vector3d>& travel_m,
              const std::vector<Wall>& walls, const std::vector<double>& wall_travel_m) const;

  // Candidates sorted by (i, j) with j as a signed number (walls first for each i).
  const std::vector<CandidatePair>& pairs() const { return pairs_; }
  // After a rebuild: index in the previous table of each new pair, or -1 if it is new.
  const std::vector<std::int32_t>& previous_index() const { return previous_index_; }

  std::size_t rebuild_count() const { return rebuilds_; }
  double margin() const { return margin_; }
  double max_margin() const { return max_margin_; }  // m, the widest the look-aheads may ask
  double wall_margin() const { return wall_margin_; }  // particle-wall pairs, m (>= margin())
  // Whether the last rebuild's margin was set by an engaged moving wall rather than by the
  // particles' own look-aheads (such a table is rebuilt once the wall has stopped).
  bool widened_by_wall() const { return widened_by_wall_; }
  // Positions at the last rebuild (empty before the first one or after invalidate()).
  const std::vector<Eigen::Vector3d>& reference_positions() const { return reference_position_; }
  // Wall points at the last rebuild (empty before the first one).
  const std::vector<Eigen::Vector3d>& reference_wall_points() const { return reference_wall_point_; }

  // Puts back a table saved from pairs(), reference_positions(), reference_wall_points(),
  // margin(), wall_margin(), widened_by_wall() and rebuild_count() (restart from a checkpoint):
  // the next update() decides exactly as the saved detector would. Empty reference positions
  // leave the table invalid (rebuilt at the next update); empty wall points: the walls' points
  // at the next update; wall_margin_m 0 (a state saved before it existed): margin_m.
  void restore(double margin_m, std::size_t rebuilds, std::vector<Eigen::Vector3d> reference_m,
               std::vector<CandidatePair> pairs,
               std::vector<Eigen::Vector3d> reference_wall_points_m = {}, double wall_margin_m = 0.0,
               bool widened_by_wall = false);

 private:
  // lookahead_max: the particles' largest look-ahead; wall_lookahead_max: the moving walls'.
  void rebuild(const ParticleSet& particles, const std::vector<Wall>& walls, double lookahead_max,
               double wall_lookahead_max);
  // The margin a rebuild takes for a largest look-ahead: 4 times it, within [min_margin,
  // max_margin], never below twice it.
  double margin_for(double lookahead_max) const {
    return std::max(std::clamp(4.0 * lookahead_max, min_margin_, max_margin_), 2.0 * lookahead_max);
  }
  // Half the shortest period less 2 r_max: how far two particles may move apart along the
  // periodic axes between rebuilds (INFINITY without periodic axes).
  double fitted_margin_m(const ParticleSet& particles) const;
  // Whether two particles moving apart across the periods by pair_lookahead_m (m) stay within
  // the fitted margin (fits_periods and check_period decide by it).
  bool pair_fits_periods(const ParticleSet& particles, double pair_lookahead_m) const;
  // Throws std::runtime_error when the fitted margin is below the two largest look-aheads
  // along the periodic axes together (pair_lookahead_m).
  void check_period(const ParticleSet& particles, double pair_lookahead_m) const;

  double min_margin_;
  double max_margin_;
  double margin_ = 0.0;
  double wall_margin_ = 0.0;
  bool widened_by_wall_ = false;
  bool valid_ = false;
  std::size_t rebuilds_ = 0;
  std::vector<Eigen::Vector3d> reference_position_;  // positions at the last rebuild
  std::vector<Eigen::Vector3d> reference_wall_point_;  // wall points at the last rebuild
  std::vector<CandidatePair> pairs_, previous_pairs_;
  std::vector<std::int32_t> previous_index_;
  CellGrid grid_;
  std::ptrdiff_t parallel_from_;
  // Per thread: its range's pairs, and the neighbours of one particle being sorted.
  std::vector<std::vector<CandidatePair>> thread_pairs_;
  std::vector<std::vector<std::uint32_t>> thread_neighbours_;
};

}  // namespace tmdem::mechanics
