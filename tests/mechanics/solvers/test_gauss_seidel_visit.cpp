// The Gauss-Seidel visit (GaussSeidelUpdate.h, its kinematics on ScalarVec3 for speed) against
// the same visit with the kinematics (ContactKinematics.h: normal_velocity, local_velocity,
// apply_impulse, rolling_velocity, apply_rolling_impulse) on Eigen::Vector3d and the rolling
// cone's projection written out: bit for bit, reactions, rolling impulses, velocities and the
// stop test's sums, over sweeps of random problems with walls, a piston and rolling
// resistance, in 3D and 2D. ScalarVec3 must round as Eigen does; this is what checks it.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "mechanics/RandomContactProblem.h"
#include "mechanics/SameBits.h"
#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/ContactProblem.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"
#include "mechanics/model/PairIndex.h"

using namespace tmdem::mechanics;
using Eigen::Vector3d;

namespace {

using tmdem::mechanics::test::same_bits;

// The visit with the kinematics on Eigen::Vector3d (the open test, u0 = U - W r, the closed-form
// solve, apply_impulse; rolling_velocity, the rolling cone's projection, apply_rolling_impulse).
ContactUpdate reference_visit(const ContactProblem& p, std::size_t c, std::vector<Vector3d>& r,
                              std::vector<Vector3d>& m, std::vector<Vector3d>& v,
                              std::vector<Vector3d>& w) {
  if (r[c] == Vector3d::Zero() && m[c] == Vector3d::Zero() && !(normal_velocity(p, c, v) < 0.0)) {
    return {};
  }
  const bool planar = p.dimension == 2;
  const Vector3d u = local_velocity<Vector3d>(p, c, v, w);
  const Vector3d u0(u[0] - p.w_n[c] * r[c][0], u[1] - p.w_t[c] * r[c][1],
                    planar ? 0.0 : u[2] - p.w_t[c] * r[c][2]);
  Vector3d next;
  solve_contact_bipotential(u0, p.w_n[c], p.w_t[c], p.mu[c], next);
  if (planar) next[2] = 0.0;
  const Vector3d dr = next - r[c];
  if (dr != Vector3d::Zero()) {
    apply_impulse(p, c, dr, v, w);
    r[c] = next;
  }
  ContactUpdate update{dr.norm(), next.norm()};
  const Vector3d& n = p.normal[c];
  Vector3d mn = m[c] - rolling_velocity<Vector3d>(p, c, w) / p.w_r[c];
  mn -= mn.dot(n) * n;
  const double limit = p.rolling_limit[c] * std::max(r[c][0], 0.0), size = mn.norm();
  if (size > limit) mn *= limit / size;
  if (planar) mn.x() = mn.y() = 0.0;
  const Vector3d dm = mn - m[c];
  if (dm != Vector3d::Zero()) {
    apply_rolling_impulse(p, c, dm, w);
    m[c] = mn;
  }
  const double scale = 1.0 / p.rolling_radius[c];
  update.change += dm.norm() * scale;
  update.total += mn.norm() * scale;
  return update;
}


class GaussSeidelVisit : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(GaussSeidelVisit, RepeatsContactProblemsOperationsBitForBit) {
  const int dimension = GetParam();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const ContactProblem p = test::random_contact_problem(dimension, seed);
    std::vector<Vector3d> r(p.size(), Vector3d::Zero()), m = r, v, w;
    p.velocities_from_reactions(r, m, v, w);
    std::vector<Vector3d> r_ref = r, m_ref = m, v_ref = v, w_ref = w;
    int solved = 0, stick = 0, slip = 0, at_rolling_limit = 0;
    for (int sweep = 0; sweep < 30; ++sweep) {
      double change = 0.0, total = 0.0, change_ref = 0.0, total_ref = 0.0;
      for (std::size_t c = 0; c < p.size(); ++c) {
        const ContactUpdate a = gauss_seidel_visit(p, c, 1.0, r[c], m, v, w);
        const ContactUpdate b = reference_visit(p, c, r_ref, m_ref, v_ref, w_ref);
        change += a.change;
        total += a.total;
        change_ref += b.change;
        total_ref += b.total;
        if (r[c][0] > 0.0) {
          ++solved;
          const double tangential = Eigen::Vector2d(r[c][1], r[c][2]).norm();
          (tangential < (1.0 - 1e-9) * p.mu[c] * r[c][0] ? stick : slip) += 1;
          if (m[c].norm() >= (1.0 - 1e-12) * p.rolling_limit[c] * r[c][0]) ++at_rolling_limit;
        }
      }
      ASSERT_TRUE(same_bits(r, r_ref)) << "seed " << seed << ", sweep " << sweep;
      ASSERT_TRUE(same_bits(m, m_ref)) << "seed " << seed << ", sweep " << sweep;
      ASSERT_TRUE(same_bits(v, v_ref)) << "seed " << seed << ", sweep " << sweep;
      ASSERT_TRUE(same_bits(w, w_ref)) << "seed " << seed << ", sweep " << sweep;
      ASSERT_TRUE(same_bits(change, change_ref) && same_bits(total, total_ref))
          << "seed " << seed << ", sweep " << sweep;
    }
    // The problems exercise every branch of the visit: closed contacts that stick and slip,
    // rolling impulses at and below their limit.
    EXPECT_GT(stick, 0);
    EXPECT_GT(slip, 0);
    EXPECT_GT(at_rolling_limit, 0);
    EXPECT_LT(at_rolling_limit, solved);
  }
}

INSTANTIATE_TEST_SUITE_P(Dimensions, GaussSeidelVisit, ::testing::Values(3, 2));
