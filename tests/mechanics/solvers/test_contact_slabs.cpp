// Slabs (ContactSlabs.h) and "nncg" sweeping them: no particle touched by two slabs of one
// phase (the promise that lets threads share a phase), a piston's contacts and the long
// look-ahead candidates in the last phase, no cut without positions or room for three slabs; "nncg" and "nlgs" sweeping slabs
// reach the lattice pile's statics (and "nncg" the reactions of "nlgs" in index order), and
// give the same bits at 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <map>
#include <vector>

#include "mechanics/SameBits.h"
#include "mechanics/PeriodicPile.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/solvers/ContactSlabs.h"
#include "mechanics/solvers/GaussSeidelSolver.h"
#include "mechanics/solvers/NncgSolver.h"
#include "mechanics/contact/SiconosResidual.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace {

// A poured pile mid-fall (look-ahead candidates of every length) and its problem.
const NscdIntegrator& falling_pile() {
  static const NscdIntegrator sim = [] {
    NscdParameters parameters = nlgs_parameters();
    parameters.tolerance = 1e-4;
    parameters.max_iterations = 300;
    NscdIntegrator s = random_pile(400, 3, 0.3, 5, parameters);
    for (int step = 0; step < 12; ++step) s.step();
    return s;
  }();
  return sim;
}

// x_i - x_j along the split axis (no period), 0 for a wall contact.
double axial_branch(const ContactProblem& problem, std::int32_t c) {
  const std::int32_t j = problem.body_j[c];
  if (is_wall(j)) return 0.0;
  const int a = problem.split_axis;
  return problem.particle_position[std::size_t(problem.body_i[c])][a] - problem.particle_position[std::size_t(j)][a];
}

// The largest sum of two particles' radii over the problem's pairs: no touching pair is
// further apart along any axis.
double largest_touching_reach(const ContactProblem& problem) {
  double reach = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c)
    if (!is_wall(problem.body_j[c])) reach = std::max(reach, problem.lever_i[c] + problem.lever_j[c]);
  return reach * (1.0 + 1e-9);
}

// Checks that slabs hold every contact of problem once, in increasing index inside a slab,
// and that within each phase no particle (nor piston) is touched by two slabs.
void expect_phases_touch_disjoint_bodies(const ContactProblem& problem, const ContactSlabs& slabs) {
  ASSERT_TRUE(slabs.valid());
  const auto& order = slabs.order();
  const auto& start = slabs.slab_start();
  const auto& phase = slabs.phase_start();
  ASSERT_EQ(phase.size(), static_cast<std::size_t>(ContactSlabs::kPhases) + 1);
  EXPECT_EQ(phase.front(), 0);
  EXPECT_EQ(static_cast<std::size_t>(phase.back()), slabs.slab_count());
  EXPECT_EQ(static_cast<std::size_t>(start.back()), problem.size());
  std::vector<int> seen(problem.size(), 0);
  for (int p = 0; p < ContactSlabs::kPhases; ++p) {
    std::map<std::size_t, std::int32_t> slab_of_body;  // bodies whose velocity a visit writes
    for (std::int32_t s = phase[p]; s < phase[p + 1]; ++s) {
      for (std::int32_t k = start[s]; k < start[s + 1]; ++k) {
        const std::int32_t c = order[k];
        ++seen[c];
        if (k > start[s]) {
          EXPECT_LT(order[k - 1], c);
        }
        const std::int32_t j = problem.body_j[c];
        std::vector<std::size_t> bodies{static_cast<std::size_t>(problem.body_i[c])};
        if (!is_wall(j)) {
          bodies.push_back(static_cast<std::size_t>(j));
        } else if (problem.inverse_mass[problem.wall_body(j)] > 0.0) {
          bodies.push_back(problem.wall_body(j));
        }
        for (const std::size_t b : bodies) {
          const auto [at, fresh] = slab_of_body.emplace(b, s);
          EXPECT_TRUE(fresh || at->second == s) << "body " << b << " in slabs " << at->second << " and " << s
                                                << " of phase " << p;
        }
      }
    }
  }
  for (std::size_t c = 0; c < problem.size(); ++c) EXPECT_EQ(seen[c], 1) << "contact " << c;
}

}  // namespace

TEST(ContactSlabs, NoParticleIsTouchedByTwoSlabsOfOnePhase) {
  const ContactProblem& problem = falling_pile().problem();
  ASSERT_GT(problem.size(), 1000u);
  ContactSlabs slabs;
  ASSERT_TRUE(slabs.update(problem, 16));
  // A 16 mm box of spheres of radius 1 and 0.7 mm: room for several slabs, not 16.
  EXPECT_GE(slabs.slab_count(), 4u);
  EXPECT_EQ(slabs.phase_start()[3] - slabs.phase_start()[2], 1);  // the piston's slab, empty
  expect_phases_touch_disjoint_bodies(problem, slabs);
}

TEST(ContactSlabs, PeriodicAxisSlabsGoRoundThePeriod) {
  // A pile falling into a box periodic along x and z: the slabs fill the period, their count
  // even, and a contact round the boundary sits in slab 0 or the last, which are neighbours
  // in different phases.
  static const NscdIntegrator sim = [] {
    NscdIntegrator s = periodic_pile(400, 0.3, 5);
    for (int step = 0; step < 12; ++step) s.step();
    return s;
  }();
  ContactProblem problem = sim.problem();
  ASSERT_GT(problem.size(), 1000u);
  ASSERT_TRUE(problem.split_periodic());
  EXPECT_EQ(problem.split_period[0], 0.0);
  EXPECT_EQ(problem.split_period[1], kPeriodicWidth);
  ContactSlabs slabs;
  ASSERT_TRUE(slabs.update(problem, 16));
  EXPECT_EQ(slabs.slab_count() % 2, 1u);  // an even count plus the piston's slab
  EXPECT_GE(slabs.slab_count(), 5u);
  expect_phases_touch_disjoint_bodies(problem, slabs);
  // Contacts round the boundary exist and all sit in the first or the last slab.
  const auto cut = static_cast<std::int32_t>(slabs.slab_count()) - 1;
  const std::int32_t even = slabs.phase_start()[1];
  const std::int32_t first = 0, last = even + (cut - 1) / 2;  // slabs 0 and cut - 1, by visit
  std::size_t across = 0;
  for (std::int32_t s = 0; s < cut; ++s) {
    for (std::int32_t k = slabs.slab_start()[s]; k < slabs.slab_start()[s + 1]; ++k) {
      const std::int32_t c = slabs.order()[k];
      const std::int32_t j = problem.body_j[c];
      if (is_wall(j)) continue;
      const int a = problem.split_axis;
      const double dx = problem.particle_position[std::size_t(problem.body_i[c])][a] -
                        problem.particle_position[std::size_t(j)][a];
      if (std::abs(dx) < 0.5 * kPeriodicWidth) continue;
      ++across;
      EXPECT_TRUE(s == first || s == last) << "contact " << c << " in slab " << s;
    }
  }
  EXPECT_GT(across, 10u);
  // Read without the period, a contact round the boundary spans the whole box: longer than
  // any touching pair, it goes to the last phase (one thread), and the cut still keeps the
  // phases apart.
  problem.split_period = {0.0, 0.0};
  ContactSlabs open;
  ASSERT_TRUE(open.update(problem, 16));
  expect_phases_touch_disjoint_bodies(problem, open);
  const std::int32_t serial = open.phase_start()[2];
  EXPECT_GE(static_cast<std::size_t>(open.slab_start()[serial + 1] - open.slab_start()[serial]), across);
}

TEST(ContactSlabs, APistonsContactsAreAloneInTheLastPhase) {
  ContactProblem problem = falling_pile().problem();
  // The floor (wall 0) made a piston: its velocity is written by every floor contact.
  problem.inverse_mass[problem.wall_body(-1)] = 0.5;
  ContactSlabs slabs;
  ASSERT_TRUE(slabs.update(problem, 16));
  expect_phases_touch_disjoint_bodies(problem, slabs);
  const std::int32_t last = slabs.phase_start()[2];
  int on_floor = 0;
  for (std::size_t c = 0; c < problem.size(); ++c) on_floor += problem.body_j[c] == -1 ? 1 : 0;
  ASSERT_GT(on_floor, 0);
  // Every floor contact is there; the others there are long look-ahead candidates.
  int floor_in_last = 0;
  for (std::int32_t k = slabs.slab_start()[last]; k < slabs.slab_start()[last + 1]; ++k) {
    const std::int32_t c = slabs.order()[k];
    if (problem.body_j[c] == -1) {
      ++floor_in_last;
      continue;
    }
    ASSERT_FALSE(is_wall(problem.body_j[c]));
    EXPECT_GT(std::abs(axial_branch(problem, c)), largest_touching_reach(problem)) << "contact " << c;
  }
  EXPECT_EQ(floor_in_last, on_floor);
}

TEST(ContactSlabs, LongCandidatesGoToTheLastPhaseAndTheSlabsAreAsWideAsTouchingPairs) {
  // Mid-fall, look-ahead pairs reach further than any two touching spheres: they are swept on
  // one thread after the slabs, whose width is then set by the touching pairs' reach, and
  // whose count is a multiple of 4 (two threads share each phase evenly).
  const ContactProblem& problem = falling_pile().problem();
  const double reach = largest_touching_reach(problem);
  std::size_t long_ones = 0;
  for (std::size_t c = 0; c < problem.size(); ++c)
    long_ones += !is_wall(problem.body_j[c]) && std::abs(axial_branch(problem, c)) > reach ? 1 : 0;
  ASSERT_GT(long_ones, 0u) << "the test needs long candidates";
  ContactSlabs slabs;
  ASSERT_TRUE(slabs.update(problem, 16));
  expect_phases_touch_disjoint_bodies(problem, slabs);
  const auto cut = slabs.slab_count() - 1;
  EXPECT_TRUE(cut == 3 || cut % 4 == 0) << cut;
  const std::int32_t last = slabs.phase_start()[2];
  EXPECT_EQ(static_cast<std::size_t>(slabs.slab_start()[last + 1] - slabs.slab_start()[last]), long_ones);
  for (std::int32_t k = 0; k < slabs.slab_start()[last]; ++k)
    EXPECT_LE(std::abs(axial_branch(problem, slabs.order()[k])), reach);
}

TEST(ContactSlabs, NoCutWithoutPositionsOrRoomForThreeSlabs) {
  ContactProblem problem = falling_pile().problem();
  ContactSlabs slabs;
  EXPECT_FALSE(slabs.update(problem, 2));  // fewer than three asked
  problem.particle_position.clear();
  EXPECT_FALSE(slabs.update(problem, 16));
  EXPECT_FALSE(slabs.valid());
  // The lattice pile is 5 spheres wide: its contacts span a whole diameter, so at most 4 slabs.
  ContactSlabs narrow;
  ASSERT_TRUE(narrow.update(lattice_pile().problem(), 16));
  EXPECT_LE(narrow.slab_count(), 4u + 1u);
}

// Sliced from the first contact (parallel_from 0): the statics of the pile, the reactions of
// "nlgs", to the tolerance a Gauss-Seidel stop test leaves.
TEST(NncgSlabs, LatticePileMatchesGaussSeidelAndStatics) {
  constexpr double tolerance = 1e-8;
  const ContactProblem& problem = lattice_pile().problem();
  SolverSettings settings = tight(tolerance);
  settings.parallel_from = 0;
  NncgSolver sliced(settings);
  const Solved solved = solve_cold(problem, sliced);
  ASSERT_TRUE(sliced.sliced());
  ASSERT_TRUE(solved.report.converged) << solved.report.residual;
  const double weight = pile_weight_impulse();
  expect_pile_statics(solved.r, 1e-6 * kPileLayers * weight);
  const Solved gs = solve_cold(problem, "nlgs", tolerance);
  EXPECT_LE(largest_difference(gs.r, solved.r), 1e-6 * kPileLayers * weight);
}

// 60 sweeps of a falling pile's problem (not converged: the bits, not the answer, compared).
TEST(NncgSlabs, SameBitsForAnyThreadCount) {
  const ContactProblem& problem = falling_pile().problem();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    SolverSettings settings = tight(1e-12);
    settings.max_iterations = 60;
    settings.parallel_from = 0;
    NncgSolver solver(settings);
    Solved solved = solve_cold(problem, solver);
    EXPECT_TRUE(solver.sliced());
    EXPECT_GT(solver.steps(), 0);
    return solved;
  };
  const int threads_before = omp_get_max_threads();
  const Solved first = run(2), second = run(2), serial = run(1);
  omp_set_num_threads(threads_before);
  EXPECT_EQ(first.report.sweeps, 60);
  EXPECT_TRUE(same_bits(first.r, second.r));
  EXPECT_TRUE(same_bits(first.r, serial.r));
  EXPECT_TRUE(same_bits(first.v, serial.v));
  EXPECT_TRUE(same_bits(first.w, serial.w));
}

// Active-set sweeps of a sliced "nncg" (Options::full_sweep_every): on the falling pile, where
// most candidates are open and some close during the solve, the partial sweeps skip the open
// ones, yet the answer passes what every candidate passes with full sweeps only: Siconos'
// residual over every candidate within the tolerance (the sweep test is the full sweeps'),
// and the pile moves as with full sweeps.
TEST(NncgSlabs, ActiveSetSweepsReachTheLawOfEveryCandidate) {
  const ContactProblem& problem = falling_pile().problem();
  auto run = [&](int full_sweep_every, int& full_sweeps) {
    SolverSettings settings = tight(1e-9);
    settings.max_iterations = 20000;
    settings.parallel_from = 0;
    NncgSolver::Options options;
    options.full_sweep_every = full_sweep_every;
    NncgSolver solver(settings, options);
    Solved solved = solve_cold(problem, solver);
    EXPECT_TRUE(solver.sliced());
    full_sweeps = solver.full_sweeps();
    return solved;
  };
  int full_every = 0, full_active = 0;
  const Solved every = run(1, full_every), active = run(4, full_active);
  ASSERT_TRUE(every.report.converged) << every.report.residual;
  ASSERT_TRUE(active.report.converged) << active.report.residual;
  EXPECT_GT(full_every, every.report.sweeps / 2);  // the last run of sweeps (after the Siconos stop's rounds)
  EXPECT_LT(full_active, active.report.sweeps / 3);  // at least 3 of 4 sweeps partial, less the confirmations
  // The partial sweeps do a full sweep's work (measured: 197 sweeps, 51 full, against 184):
  // had they skipped contacts that mattered, about 4 times the sweeps.
  EXPECT_LT(active.report.sweeps, 3 * every.report.sweeps / 2);
  const double q_norm = free_velocity_norm(problem);
  const double e_every = siconos_residual(problem, every.r, {}, every.v, every.w, q_norm);
  const double e_active = siconos_residual(problem, active.r, {}, active.v, active.w, q_norm);
  EXPECT_LT(e_every, 1e-7);
  EXPECT_LT(e_active, 1e-7);
  // The two answers move the pile alike (a frictional problem's answer need not be unique:
  // the bound is the tolerance's order, relative to the fastest free speed).
  double largest = 0.0, fastest = 0.0;
  for (std::size_t p = 0; p < every.v.size(); ++p) {
    largest = std::max(largest, (active.v[p] - every.v[p]).norm());
    fastest = std::max(fastest, every.v[p].norm());
  }
  EXPECT_LT(largest, 1e-5 * fastest) << largest << " " << fastest;
}

// "nlgs" sliced (the penetration correction's solver): the statics, and the same bits at 1 and
// 2 threads after 60 sweeps of the falling pile.
TEST(GaussSeidelSlabs, LatticePileStaticsAndSameBitsForAnyThreadCount) {
  constexpr double tolerance = 1e-8;
  SolverSettings sliced_settings = tight(tolerance);
  sliced_settings.parallel_from = 0;
  GaussSeidelSolver sliced(sliced_settings);
  const Solved solved = solve_cold(lattice_pile().problem(), sliced);
  ASSERT_TRUE(sliced.sliced());
  ASSERT_TRUE(solved.report.converged) << solved.report.residual;
  expect_pile_statics(solved.r, 1e-6 * kPileLayers * pile_weight_impulse());

  const ContactProblem& problem = falling_pile().problem();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    SolverSettings settings = tight(1e-12);
    settings.max_iterations = 60;
    settings.parallel_from = 0;
    GaussSeidelSolver solver(settings);
    Solved out = solve_cold(problem, solver);
    EXPECT_TRUE(solver.sliced());
    return out;
  };
  const int threads_before = omp_get_max_threads();
  const Solved first = run(2), serial = run(1);
  omp_set_num_threads(threads_before);
  EXPECT_EQ(first.report.sweeps, 60);
  EXPECT_TRUE(same_bits(first.r, serial.r));
  EXPECT_TRUE(same_bits(first.v, serial.v));
  EXPECT_TRUE(same_bits(first.w, serial.w));
}
