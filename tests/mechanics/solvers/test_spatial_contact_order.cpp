// SpatialContactOrder (the contact problem handed to the solver with its bodies along a
// Morton curve): a permutation that maps back exactly, and a solve in that order reaching the
// answer of the solve in the problem's own order (exact statics of the lattice pile; the same
// reactions on random piles to the solver's tolerance); an integrator using it keeps its bits
// from run to run and across a restart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/model/PairIndex.h"
#include "mechanics/solvers/SpatialContactOrder.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// A 3D pile of 40 spheres with rolling resistance, after `steps` steps of pouring.
const NscdIntegrator& rolling_pile() {
  static const NscdIntegrator sim = [] {
    NscdIntegrator s = random_pile(40, 3, 0.3, 7, {}, 0.1);
    for (int k = 0; k < 3000 && !(k > 10 && s.max_speed() < 1e-6); ++k) s.step();
    return s;
  }();
  return sim;
}

bool is_identity(const std::vector<std::int32_t>& v) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (v[k] != static_cast<std::int32_t>(k)) return false;
  return true;
}

struct SolvedBoth {
  Solved plain, ordered;
};

// Cold solves of `problem` in its own order and through SpatialContactOrder, to `tolerance`.
SolvedBoth solve_both(const ContactProblem& problem, const std::vector<Vector3d>& position,
                      const std::string& solver, double tolerance, SpatialContactOrder& order) {
  SolvedBoth s;
  std::vector<Vector3d> m_plain(problem.rolling ? problem.size() : 0, Vector3d::Zero());
  std::vector<Vector3d> m_ordered = m_plain;
  s.plain.r.assign(problem.size(), Vector3d::Zero());
  s.ordered.r = s.plain.r;
  s.plain.report = make_contact_solver(solver, test::tight(tolerance))
                       ->solve_with_rolling(problem, s.plain.r, m_plain, s.plain.v, s.plain.w);
  order.update(problem, position, 2.0 * kRadius);
  auto ordered_solver = make_contact_solver(solver, test::tight(tolerance));
  s.ordered.report = order.solve(*ordered_solver, problem, s.ordered.r, m_ordered, s.ordered.v, s.ordered.w);
  return s;
}

// A solver that records the problem it is handed and leaves the reactions as they are.
class ProblemSpy final : public ContactSolver {
 public:
  std::string_view name() const override { return "spy"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Vector3d>& r, std::vector<Vector3d>& m,
                                 std::vector<Vector3d>& velocity, std::vector<Vector3d>& angular_velocity) override {
    seen = problem;
    problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    return {};
  }
  ContactProblem seen;
};

}  // namespace

// The copy handed to the solver keeps the problem-wide settings, among them the stop test's cap
// on loaded contacts (ContactProblem::stop_speed; the copy once left it at 0, so beds from
// NscdParameters::spatial_order_from particles on were judged without it).
TEST(SpatialContactOrder, OrderedCopyKeepsTheProblemWideSettings) {
  const NscdIntegrator& sim = rolling_pile();
  ContactProblem problem = sim.problem();
  ASSERT_TRUE(problem.rolling);
  problem.stop_speed = 0.25;
  SpatialContactOrder order;
  order.update(problem, sim.particles().position, 2.0 * kRadius);
  ProblemSpy spy;
  std::vector<Vector3d> r(problem.size(), Vector3d::Zero()), m = r, v, w;
  order.solve(spy, problem, r, m, v, w);
  EXPECT_EQ(spy.seen.stop_speed, 0.25);
  EXPECT_EQ(spy.seen.rolling, problem.rolling);
  EXPECT_EQ(spy.seen.compliant, problem.compliant);
  EXPECT_EQ(spy.seen.dimension, problem.dimension);
  EXPECT_EQ(spy.seen.particle_count, problem.particle_count);
  EXPECT_EQ(spy.seen.split_axis, problem.split_axis);
  EXPECT_EQ(spy.seen.size(), problem.size());
}

TEST(SpatialContactOrder, PermutesBodiesAndSortsContactsByThem) {
  const NscdIntegrator& sim = rolling_pile();
  const ContactProblem& problem = sim.problem();
  ASSERT_GT(problem.size(), 50u);
  SpatialContactOrder order;
  order.update(problem, sim.particles().position, 2.0 * kRadius);
  // Bodies: a permutation of the particles, and not the identity (the test would prove nothing).
  std::vector<std::int32_t> sorted = order.body_number();
  std::sort(sorted.begin(), sorted.end());
  ASSERT_TRUE(is_identity(sorted));
  EXPECT_FALSE(is_identity(order.body_number()));
  // Contacts: a permutation of the problem's.
  sorted = order.contact_order();
  std::sort(sorted.begin(), sorted.end());
  ASSERT_EQ(sorted.size(), problem.size());
  ASSERT_TRUE(is_identity(sorted));

  std::vector<Vector3d> r(problem.size(), Vector3d::Zero()), m = r, v, w;
  auto solver = make_contact_solver("nlgs", test::tight(1e-6));
  order.solve(*solver, problem, r, m, v, w);
  const ContactProblem& q = order.ordered_problem();
  ASSERT_EQ(q.size(), problem.size());
  ASSERT_EQ(q.body_count(), problem.body_count());
  std::int32_t previous = -1;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const auto c = static_cast<std::size_t>(order.contact_order()[k]);
    const std::int32_t i = problem.body_i[c], j = problem.body_j[c];
    // The same contact, its bodies renumbered (walls keep their code), every value copied.
    EXPECT_EQ(q.body_i[k], order.body_number()[static_cast<std::size_t>(i)]);
    EXPECT_EQ(q.body_j[k], is_wall(j) ? j : order.body_number()[static_cast<std::size_t>(j)]);
    EXPECT_EQ(q.normal[k], problem.normal[c]);
    EXPECT_EQ(q.tangent2[k], problem.tangent2[c]);
    EXPECT_EQ(q.bias[k], problem.bias[c]);
    EXPECT_EQ(q.w_t[k], problem.w_t[c]);
    EXPECT_EQ(q.rolling_limit[k], problem.rolling_limit[c]);
    // Sorted by the smaller body number.
    const std::int32_t first = is_wall(q.body_j[k]) ? q.body_i[k] : std::min(q.body_i[k], q.body_j[k]);
    EXPECT_GE(first, previous) << "contact " << k;
    previous = first;
  }
  for (std::size_t p = 0; p < problem.particle_count; ++p) {
    const auto b = static_cast<std::size_t>(order.body_number()[p]);
    EXPECT_EQ(q.inverse_mass[b], problem.inverse_mass[p]);
    EXPECT_EQ(q.free_velocity[b], problem.free_velocity[p]);
  }
  // A problem that is not the one the order was made for is refused.
  SpatialContactOrder stale;
  EXPECT_THROW(stale.solve(*solver, problem, r, m, v, w), std::logic_error);
  EXPECT_THROW(stale.update(problem, {}, 2.0 * kRadius), std::invalid_argument);
}

// The lattice pile's statics are exact (each contact carries the column above it): the
// ordered solve meets them, and the unordered solve's reactions, to the tolerance.
TEST(SpatialContactOrder, LatticePileMeetsTheStaticsLikeTheUnorderedSolve) {
  const NscdIntegrator& sim = lattice_pile();
  const ContactProblem& problem = sim.problem();
  SpatialContactOrder order;
  const SolvedBoth s = solve_both(problem, sim.particles().position, "nlgs", 1e-10, order);
  EXPECT_FALSE(is_identity(order.body_number()));
  ASSERT_TRUE(s.plain.report.converged);
  ASSERT_TRUE(s.ordered.report.converged) << s.ordered.report.residual;
  const double weight = pile_weight_impulse();
  expect_pile_statics(s.ordered.r, 1e-8 * kPileLayers * weight);
  EXPECT_LE(largest_difference(s.plain.r, s.ordered.r), 1e-8 * kPileLayers * weight);
  // The velocities mapped back are those of the reactions mapped back.
  EXPECT_LE(natural_map_residual(problem, s.ordered.r, s.ordered.v, s.ordered.w), 1e-9);
  std::vector<Vector3d> v, w;
  problem.velocities_from_reactions(s.ordered.r, v, w);
  for (std::size_t b = 0; b < v.size(); ++b) EXPECT_LE((v[b] - s.ordered.v[b]).norm(), 1e-15) << b;
}

// The pile with friction and rolling resistance, settled: its reactions are not unique (more
// contacts than a pile needs; measured: two converged solves in the two orders differ by
// 1.6% of the largest reaction), so the two solves are compared by what every solution
// shares: the body velocities (W r is unique where r is not), the floor's load, and the
// residual of the reactions mapped back, computed on the problem in its own order.
TEST(SpatialContactOrder, SettledRollingPileGivesTheAnswerOfTheUnorderedSolve) {
  const NscdIntegrator& sim = rolling_pile();
  ASSERT_LT(sim.max_speed(), 1e-6) << "the pile did not settle";
  const ContactProblem& problem = sim.problem();
  ASSERT_TRUE(problem.rolling);
  SpatialContactOrder order;
  std::vector<Vector3d> m_plain(problem.size(), Vector3d::Zero()), m_ordered = m_plain;
  Solved plain, ordered;
  plain.r.assign(problem.size(), Vector3d::Zero());
  ordered.r = plain.r;
  SolverSettings settings = test::tight(1e-10);
  settings.stall_sweeps = 1 << 30;
  plain.report = make_contact_solver("nlgs", settings)
                     ->solve_with_rolling(problem, plain.r, m_plain, plain.v, plain.w);
  order.update(problem, sim.particles().position, 2.0 * kRadius);
  EXPECT_FALSE(is_identity(order.body_number()));
  ordered.report = order.solve(*make_contact_solver("nlgs", settings), problem, ordered.r,
                               m_ordered, ordered.v, ordered.w);
  ASSERT_TRUE(plain.report.converged) << plain.report.residual;
  ASSERT_TRUE(ordered.report.converged) << ordered.report.residual;
  EXPECT_LE(natural_map_residual(problem, ordered.r, m_ordered, ordered.v, ordered.w), 1e-9);
  EXPECT_LE(natural_map_residual(problem, plain.r, m_plain, plain.v, plain.w), 1e-9);
  // Velocities on the scale of what gravity gives in a step, g h.
  const double speed = kG * sim.parameters().time_step;
  for (std::size_t b = 0; b < problem.particle_count; ++b) {
    EXPECT_LE((plain.v[b] - ordered.v[b]).norm(), 1e-7 * speed) << "body " << b;
  }
  double floor_plain = 0.0, floor_ordered = 0.0, weight = 0.0;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (problem.body_j[c] != wall_code<std::int32_t>(0)) continue;
    floor_plain += global_impulse(problem, c, plain.r[c]).y();
    floor_ordered += global_impulse(problem, c, ordered.r[c]).y();
  }
  for (std::size_t p = 0; p < problem.particle_count; ++p) weight += speed / problem.inverse_mass[p];
  EXPECT_NEAR(floor_plain, weight, 1e-6 * weight);  // the floor carries the pile
  EXPECT_NEAR(floor_ordered, floor_plain, 1e-9 * weight);
}

// Integrator: the ordered run is another run (other visiting order) that reproduces its own
// bits, and it comes to the same place as the unordered one.
TEST(SpatialContactOrder, IntegratorRunsAreReproducible) {
  NscdParameters ordered_parameters = nlgs_parameters();
  ordered_parameters.spatial_order_from = 0;
  NscdParameters plain_parameters = nlgs_parameters();
  plain_parameters.spatial_order_from = std::numeric_limits<std::size_t>::max();
  NscdIntegrator a = random_pile(40, 3, 0.3, 7, ordered_parameters, 0.1);
  NscdIntegrator b = random_pile(40, 3, 0.3, 7, ordered_parameters, 0.1);
  NscdIntegrator plain = random_pile(40, 3, 0.3, 7, plain_parameters, 0.1);
  bool differs = false;
  for (int k = 0; k < 150; ++k) {
    a.step();
    b.step();
    plain.step();
    ASSERT_EQ(0, std::memcmp(a.particles().velocity.data(), b.particles().velocity.data(),
                             a.particles().size() * sizeof(Vector3d))) << "step " << k;
    ASSERT_EQ(0, std::memcmp(a.particles().position.data(), b.particles().position.data(),
                             a.particles().size() * sizeof(Vector3d))) << "step " << k;
    differs = differs || std::memcmp(a.particles().velocity.data(), plain.particles().velocity.data(),
                                     a.particles().size() * sizeof(Vector3d)) != 0;
  }
  EXPECT_TRUE(differs) << "the order was not used: the test would prove nothing";
  // Both piles came down to the floor (mean height within a fraction of a radius).
  double ya = 0.0, yp = 0.0;
  for (std::size_t p = 0; p < a.particles().size(); ++p) {
    ya += a.particles().position[p].y();
    yp += plain.particles().position[p].y();
  }
  EXPECT_NEAR(ya / a.particles().size(), yp / plain.particles().size(), 0.2 * kRadius);
}
