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

// Draws of our own (std::uniform_real_distribution's are implementation-defined).
struct Draws {
  std::mt19937_64 engine;
  explicit Draws(std::uint64_t seed) : engine(seed) {}
  double uniform(double a, double b) {
    return a + (b - a) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
  }
  Vector3d vector(double size, int dimension) {
    return Vector3d(uniform(-size, size), uniform(-size, size), dimension == 3 ? uniform(-size, size) : 0.0);
  }
};

// 40 spheres (mass ~1e-4 kg, radius ~1 mm), a fixed floor and a piston (wall bodies 40 and 41),
// 160 contacts between random pairs or a sphere and a wall, each with a random unit normal and
// its tangents, Delassus blocks from the bodies (w_n = 1/m_i + 1/m_j, w_t adds R^2/I for each
// sphere, w_r = 1/I_i + 1/I_j), a random position term and warm start: open, sticking and
// slipping contacts, at and below the rolling limit.
ContactProblem random_problem(int dimension, std::uint64_t seed) {
  Draws d(seed);
  ContactProblem p;
  p.dimension = dimension;
  p.rolling = true;
  const int spheres = 40, contacts = 160;
  std::vector<double> radius(spheres);
  for (int b = 0; b < spheres; ++b) {
    radius[b] = d.uniform(0.5e-3, 1e-3);
    const double mass = d.uniform(0.5e-4, 2e-4), inertia = 0.4 * mass * radius[b] * radius[b];
    p.inverse_mass.push_back(1.0 / mass);
    p.inverse_inertia.push_back(1.0 / inertia);
    p.free_velocity.push_back(d.vector(0.05, dimension));
    Vector3d spin = d.vector(50.0, 3);
    if (dimension == 2) spin = Vector3d(0.0, 0.0, spin.z());
    p.free_angular_velocity.push_back(spin);
  }
  p.add_fixed_wall_bodies(2);
  p.inverse_mass[spheres + 1] = 1.0 / 1e-3;  // the piston
  p.free_velocity[spheres + 1] = Vector3d(0.0, -0.01, 0.0);
  p.resize_contacts(contacts);
  for (int c = 0; c < contacts; ++c) {
    const int i = static_cast<int>(d.engine() % spheres);
    int j = static_cast<int>(d.engine() % (spheres + 2));
    if (j == i) j = (i + 1) % spheres;
    const bool wall = j >= spheres;
    Vector3d n = d.vector(1.0, dimension);
    if (wall) n = Vector3d(0.0, 1.0, 0.0);  // the walls' normal, along which the piston moves
    n.normalize();
    const Vector3d t1 = dimension == 2 ? Vector3d(-n.y(), n.x(), 0.0) : n.unitOrthogonal();
    const double im_j = p.inverse_mass[j];  // 0 for the floor
    const double ii_i = p.inverse_inertia[i], ii_j = wall ? 0.0 : p.inverse_inertia[j];
    const double lever_j = wall ? 0.0 : radius[j];
    p.body_i[c] = i;
    p.body_j[c] = wall ? wall_code<std::int32_t>(static_cast<std::size_t>(j - spheres)) : j;
    p.normal[c] = n;
    p.tangent1[c] = t1;
    p.tangent2[c] = n.cross(t1);
    p.lever_i[c] = radius[i];
    p.lever_j[c] = lever_j;
    p.w_n[c] = p.inverse_mass[i] + im_j;
    p.w_t[c] = p.w_n[c] + radius[i] * radius[i] * ii_i + lever_j * lever_j * ii_j;
    p.bias[c] = d.uniform(-0.02, 0.02);
    p.mu[c] = d.uniform(0.1, 0.6);
    p.rolling_radius[c] = wall ? radius[i] : radius[i] * radius[j] / (radius[i] + radius[j]);
    p.rolling_limit[c] = d.uniform(0.0, 0.1) * p.rolling_radius[c];
    p.w_r[c] = ii_i + ii_j;
  }
  return p;
}

// The visit as ContactProblem's operations give it (the open test, u0 = U - W r, the closed-form
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
    const ContactProblem p = random_problem(dimension, seed);
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
