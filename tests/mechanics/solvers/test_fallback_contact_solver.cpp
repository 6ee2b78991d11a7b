// FallbackContactSolver.h's near miss: when neither solver converged and the better result is
// within near_miss x the tolerance of Siconos' residual, the first solver runs once more from it,
// and its result is kept only if nearer the law; further off, the result stays as it was.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "mechanics/ColumnStatics.h"
#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/SolverTestPile.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/solvers/FallbackContactSolver.h"
#include "mechanics/solvers/NncgSolver.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;

namespace {

// A second solver that never converges and leaves the reactions as they are.
class NeverConverges final : public ContactSolver {
 public:
  std::string_view name() const override { return "never"; }
  SolveReport solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                 std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
                                 std::vector<Eigen::Vector3d>& angular_velocity) override {
    problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    return {};
  }
};

// nncg cut to 20 sweeps (its own test never stops it), then NeverConverges; the near miss
// judged against `tolerance`.
std::unique_ptr<FallbackContactSolver> cut_nncg(double tolerance) {
  SolverSettings settings = tight(1e-15);
  settings.max_iterations = 20;
  return std::make_unique<FallbackContactSolver>("cut", std::make_unique<NncgSolver>(settings),
                                                 std::make_unique<NeverConverges>(), 1000000, tolerance, 2.0);
}

double siconos_of(const ContactProblem& problem, const Solved& s) {
  return siconos_residual(problem, s.r, {}, s.v, s.w, free_velocity_norm(problem));
}

}  // namespace

// The heavy-on-light column (Gauss-Seidel contracts by 0.9995 a sweep on it): 20 sweeps leave it
// at e1. Judged a near miss (e1 = 1.5 x the tolerance), nncg runs 20 sweeps more from there and
// ends nearer the law; judged far (3 x), the result is the first 20 sweeps', bit for bit.
TEST(FallbackContactSolver, NearMissGetsTheFirstSolverOnceMore) {
  std::vector<double> masses;
  for (int k = 0; k < 5; ++k) masses.insert(masses.end(), {1e-3, 1.0});
  const NscdIntegrator sim = column(masses);
  const ContactProblem& problem = sim.problem();
  SolverSettings twenty = tight(1e-15);
  twenty.max_iterations = 20;
  NncgSolver plain(twenty);
  const Solved first = solve_cold(problem, plain);
  const double e1 = siconos_of(problem, first);
  ASSERT_FALSE(first.report.converged);
  ASSERT_GT(e1, 0.0);

  auto near = cut_nncg(e1 / 1.5);
  const Solved again = solve_cold(problem, *near);
  EXPECT_EQ(near->fallbacks(), 1);
  EXPECT_EQ(near->near_misses(), 1);
  EXPECT_EQ(again.report.sweeps, 40);
  EXPECT_LT(siconos_of(problem, again), e1);

  auto far = cut_nncg(e1 / 3.0);
  const Solved kept = solve_cold(problem, *far);
  EXPECT_EQ(far->fallbacks(), 1);
  EXPECT_EQ(far->near_misses(), 0);
  EXPECT_EQ(kept.report.sweeps, 20);
  for (std::size_t c = 0; c < problem.size(); ++c) EXPECT_EQ(kept.r[c], first.r[c]) << "contact " << c;
}
