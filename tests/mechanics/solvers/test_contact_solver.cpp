// The contact problem apart from its solver: registry by name, and a solver driven directly
// on a hand-built problem against closed-form answers.
#include <gtest/gtest.h>

#include <string>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/ContactSolverRegistry.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

TEST(ContactSolverRegistry, KnownNameGivesThatSolver) {
  ASSERT_FALSE(contact_solver_names().empty());
  EXPECT_EQ(contact_solver_names().front(), "nlgs");
  for (const auto& name : contact_solver_names()) {
    EXPECT_EQ(make_contact_solver(name, {})->name(), name);
  }
}

TEST(ContactSolverRegistry, UnknownNameListsTheValidOnes) {
  try {
    make_contact_solver("gauss_seidle", {});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"gauss_seidle\""), std::string::npos) << what;
    for (const auto& name : contact_solver_names()) {
      EXPECT_NE(what.find("\"" + name + "\""), std::string::npos) << what;
    }
  }
}

namespace {

// Two spheres stacked on a floor, at rest and touching: the problem of one step h under
// gravity g, with the two contacts (floor-0, 0-1). Masses m0, m1.
ContactProblem stack_problem(double m0, double m1, double h, double g) {
  ContactProblem p;
  p.dimension = 3;
  p.inverse_mass = {1.0 / m0, 1.0 / m1};
  p.inverse_inertia = {1.0, 1.0};  // irrelevant: no tangential load
  p.free_velocity = {Vector3d(0, -g * h, 0), Vector3d(0, -g * h, 0)};
  p.free_angular_velocity = {Vector3d::Zero(), Vector3d::Zero()};
  p.resize_contacts(2);
  // Contact 0: sphere 0 on the floor (wall 0). Contact 1: sphere 0 (i) under sphere 1 (j),
  // normal from j to i: down.
  p.body_i = {0, 0};
  p.body_j = {-1, 1};
  p.normal = {Vector3d(0, 1, 0), Vector3d(0, -1, 0)};
  p.tangent1 = {Vector3d(1, 0, 0), Vector3d(1, 0, 0)};
  p.tangent2 = {Vector3d(0, 0, -1), Vector3d(0, 0, 1)};
  p.lever_i = {1e-3, 1e-3};
  p.lever_j = {0.0, 1e-3};
  p.w_n = {1.0 / m0, 1.0 / m0 + 1.0 / m1};
  p.w_t = {1.0 / m0 + 1e-6, 1.0 / m0 + 1.0 / m1 + 2e-6};
  p.bias = {0.0, 0.0};
  p.mu = {0.3, 0.3};
  p.add_fixed_wall_bodies(1);  // the floor
  return p;
}

}  // namespace

TEST(GaussSeidelSolver, StackCarriesTheWeightAboveAndStops) {
  const double m0 = 2.0, m1 = 3.0, h = 1e-3, g = 9.81;
  const ContactProblem problem = stack_problem(m0, m1, h, g);
  SolverSettings settings;
  settings.tolerance = 1e-12;
  auto solver = make_contact_solver("nlgs", settings);
  std::vector<Vector3d> r(2, Vector3d::Zero()), v, w;
  const SolveReport report = solver->solve(problem, r, v, w);
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR(r[0][0], (m0 + m1) * g * h, 1e-9 * (m0 + m1) * g * h);
  EXPECT_NEAR(r[1][0], m1 * g * h, 1e-9 * m1 * g * h);
  ASSERT_EQ(v.size(), 3u);  // two spheres and the floor's (immobile) wall body
  EXPECT_LT(v[0].norm() + v[1].norm(), 1e-9 * g * h);
  // Warm-started from the answer, it stops at once (a second sweep may confirm round-off).
  const SolveReport warm = solver->solve(problem, r, v, w);
  EXPECT_TRUE(warm.converged);
  EXPECT_LE(warm.sweeps, 2);
}

