// The one sweep engine (GaussSeidelSweep.h) in each of its visiting orders, with and without
// the active set: where the orders visit the same contacts in the same sequence (a colouring
// of one contact per colour, in index order; body blocks that own no contact) they must give
// the same bits as the index order, and the index order with every sweep full the bits of the
// symmetric Gauss-Seidel sweeps written out.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "mechanics/RandomContactProblem.h"
#include "mechanics/SameBits.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/GaussSeidelSweep.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

namespace {

struct SweepResult {
  std::vector<Vector3d> r, m, v, w;
  int sweeps = 0;
};

// Solves `problem` from zero reactions in `order`; tolerance -1: no sweep meets it, so every
// run does exactly max_iterations sweeps whatever the order's sums.
SweepResult sweep_with(const ContactProblem& problem, GaussSeidelSweep::Order order, int full_sweep_every) {
  SolverSettings settings;
  settings.tolerance = -1.0;
  settings.max_iterations = 25;
  settings.stall_sweeps = 1000;
  const std::size_t count = problem.size();
  std::vector<std::int32_t> singletons(count + 1), no_block(count, -1);
  std::iota(singletons.begin(), singletons.end(), 0);
  GaussSeidelSweep::Options options;
  options.full_sweep_every = full_sweep_every;
  options.stall_sweeps = settings.stall_sweeps;
  options.colour_start = &singletons;
  options.block_of = &no_block;
  SweepResult out;
  out.r.assign(count, Vector3d::Zero());
  out.m.assign(count, Vector3d::Zero());
  GaussSeidelSweep sweep;
  GaussSeidelSweepHooks hooks;
  const GaussSeidelSweepState state{problem, out.r, out.m, out.v, out.w};
  switch (order) {
    case GaussSeidelSweep::Order::index:
      out.sweeps = sweep.solve<GaussSeidelSweep::Order::index>(settings, options, state, hooks).sweeps;
      break;
    case GaussSeidelSweep::Order::colour:
      out.sweeps = sweep.solve<GaussSeidelSweep::Order::colour>(settings, options, state, hooks).sweeps;
      break;
    case GaussSeidelSweep::Order::body_block:
      out.sweeps = sweep.solve<GaussSeidelSweep::Order::body_block>(settings, options, state, hooks).sweeps;
      break;
    case GaussSeidelSweep::Order::slab:  // needs positions: test_contact_slabs.cpp
      ADD_FAILURE() << "slab order is tested with a cut of its own";
      break;
  }
  return out;
}

bool same(const SweepResult& a, const SweepResult& b) {
  return a.sweeps == b.sweeps && test::same_bits(a.r, b.r) && test::same_bits(a.m, b.m) &&
         test::same_bits(a.v, b.v) && test::same_bits(a.w, b.w);
}

class GaussSeidelSweepOrders : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(GaussSeidelSweepOrders, SameVisitsGiveTheSameBits) {
  const int dimension = GetParam();
  for (std::uint64_t seed : {1u, 2u}) {
    const ContactProblem problem = test::random_contact_problem(dimension, seed);
    for (int every : {1, 4}) {
      const SweepResult index = sweep_with(problem, GaussSeidelSweep::Order::index, every);
      EXPECT_EQ(index.sweeps, 25);
      EXPECT_TRUE(same(index, sweep_with(problem, GaussSeidelSweep::Order::colour, every)))
          << "seed " << seed << ", full sweep every " << every;
      EXPECT_TRUE(same(index, sweep_with(problem, GaussSeidelSweep::Order::body_block, every)))
          << "seed " << seed << ", full sweep every " << every;
    }
  }
}

TEST_P(GaussSeidelSweepOrders, IndexOrderIsSymmetricGaussSeidel) {
  const ContactProblem problem = test::random_contact_problem(GetParam(), 3);
  const SweepResult engine = sweep_with(problem, GaussSeidelSweep::Order::index, 1);
  SweepResult written;
  written.r.assign(problem.size(), Vector3d::Zero());
  written.m = written.r;
  problem.velocities_from_reactions(written.r, written.m, written.v, written.w);
  for (int sweep = 1; sweep <= 25; ++sweep) {
    for (std::size_t visit = 0; visit < problem.size(); ++visit) {
      const std::size_t c = sweep % 2 == 1 ? visit : problem.size() - 1 - visit;
      if (problem.solvable(c)) gauss_seidel_visit(problem, c, 1.0, written.r[c], written.m, written.v, written.w);
    }
  }
  written.sweeps = 25;
  EXPECT_TRUE(same(engine, written));
}

INSTANTIATE_TEST_SUITE_P(Dimensions, GaussSeidelSweepOrders, ::testing::Values(3, 2));
