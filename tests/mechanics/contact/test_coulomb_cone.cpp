// The bipotential local law: the projection's three statuses, and the local solver against
// the closed-form solution of one contact with a diagonal Delassus block.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mechanics/contact/CoulombCone.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

TEST(CoulombCone, ProjectionStatuses) {
  const double mu = 0.5;
  // Stick: inside the cone, unchanged.
  EXPECT_EQ(project_onto_coulomb_cone(Vector3d(2.0, 0.6, -0.8), mu), Vector3d(2.0, 0.6, -0.8));
  // No contact: inside the polar cone (mu |t| <= -n).
  EXPECT_EQ(project_onto_coulomb_cone(Vector3d(-2.0, 3.0, 0.0), mu), Vector3d::Zero());
  // Slip: tau = (1, 3, 4): |t| = 5, r_n = (1 + 2.5) / 1.25 = 2.8, r_t = 1.4 * (0.6, 0.8).
  const Vector3d slip = project_onto_coulomb_cone(Vector3d(1.0, 3.0, 4.0), mu);
  EXPECT_NEAR(slip[0], 2.8, 1e-15);
  EXPECT_NEAR(slip[1], 0.84, 1e-15);
  EXPECT_NEAR(slip[2], 1.12, 1e-15);
  // The slip result is the nearest cone point: tau - r is normal to the cone at r.
  const Vector3d d = Vector3d(1.0, 3.0, 4.0) - slip;
  EXPECT_NEAR(d.dot(slip), 0.0, 1e-14);
  // Frictionless cone: the normal part only, and nothing for a pulling tau.
  EXPECT_EQ(project_onto_coulomb_cone(Vector3d(-1.0, 0.0, 0.0), 0.0), Vector3d::Zero());
  EXPECT_EQ(project_onto_coulomb_cone(Vector3d(-1.0, 0.0, 0.0), 0.5), Vector3d::Zero());
  EXPECT_EQ(project_onto_coulomb_cone(Vector3d(1.0, 3.0, 4.0), 0.0), Vector3d(1.0, 0.0, 0.0));
}

// Closed form for u = u0 + diag(wn, wt, wt) r under the De Saxce law.
static Vector3d exact_single_contact(const Vector3d& u0, double wn, double wt, double mu) {
  if (u0[0] >= 0.0) return Vector3d::Zero();                   // separating: no contact
  const double rn = -u0[0] / wn;                               // u_n = 0 when in contact
  const Vector3d stick_t(0.0, -u0[1] / wt, -u0[2] / wt);
  if (stick_t.norm() <= mu * rn) return Vector3d(rn, stick_t[1], stick_t[2]);
  const double ut = std::hypot(u0[1], u0[2]);                  // slip: r_t opposes u0_t
  return Vector3d(rn, -mu * rn * u0[1] / ut, -mu * rn * u0[2] / ut);
}

TEST(CoulombCone, LocalSolverMatchesClosedForm) {
  std::mt19937_64 rng(11);
  auto uniform = [&](double a, double b) { return a + (b - a) * static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 2000; ++trial) {
    const double wn = uniform(0.1, 10.0), wt = wn * uniform(1.0, 4.0), mu = uniform(0.0, 1.2);
    const Vector3d u0(uniform(-1, 0.3), uniform(-1, 1), uniform(-1, 1));
    const Vector3d expected = exact_single_contact(u0, wn, wt, mu);
    const Vector3d warm(uniform(0, 1), uniform(-1, 1), uniform(-1, 1));  // arbitrary warm start
    Vector3d r = warm;
    solve_contact_bipotential_iterative(u0, wn, wt, mu, r, 1e-14, 5000);
    const double scale = std::max(1.0, expected.norm());
    EXPECT_LT((r - expected).norm(), 1e-9 * scale) << "trial " << trial;
    // Reaction in the cone.
    EXPECT_GE(r[0], 0.0);
    EXPECT_LE(std::hypot(r[1], r[2]), mu * r[0] * (1 + 1e-12) + 1e-15);
    // The closed form used by the integrator: the same fixed point, to round-off, in one pass.
    Vector3d exact = warm;
    EXPECT_EQ(solve_contact_bipotential(u0, wn, wt, mu, exact), 1);
    EXPECT_LT((exact - expected).norm(), 1e-14 * scale) << "trial " << trial;
    EXPECT_LT((exact - r).norm(), 1e-9 * scale) << "trial " << trial;
    EXPECT_GE(exact[0], 0.0);
    EXPECT_LE(std::hypot(exact[1], exact[2]), mu * exact[0] * (1 + 1e-12) + 1e-15);
    const int status = expected[0] == 0.0 ? 0 : (std::hypot(expected[1], expected[2]) < mu * expected[0] * (1 - 1e-12) ? 1 : 2);
    ++counts[status];
  }
  // All three statuses were exercised.
  EXPECT_GT(counts[0], 50);
  EXPECT_GT(counts[1], 50);
  EXPECT_GT(counts[2], 50);
}
