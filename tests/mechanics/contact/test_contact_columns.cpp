// contact_columns (ContactKinematics.h): the columns of M^-1 H_c at unit mobilities, scaled by a
// body's inverse mass and inertia, are what apply_impulse does to that body for any local impulse
// (particles on both sides, a fixed floor, a piston), to round-off; contact_rows, the rows of
// H_c^T for one particle, are their transpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mechanics/RandomContactProblem.h"
#include "mechanics/contact/ContactKinematics.h"

namespace tmdem::mechanics {

TEST(ContactColumns, ScaledColumnsAreWhatAnImpulseDoesToEachSide) {
  for (int dimension : {2, 3}) {
    const ContactProblem problem = test::random_contact_problem(dimension, 7);
    test::Draws d(11);
    const std::size_t bodies = problem.body_count();
    int walls = 0, pistons = 0;
    for (std::size_t c = 0; c < problem.size(); ++c) {
      const Eigen::Vector3d r = d.vector(1e-6, 3);
      std::vector<Eigen::Vector3d> v(bodies, Eigen::Vector3d::Zero()), w(bodies, Eigen::Vector3d::Zero());
      apply_impulse(problem, c, r, v, w);
      const ContactColumns columns = contact_columns(problem, c);
      const std::int32_t j = problem.body_j[c];
      const std::size_t side_body[2] = {std::size_t(problem.body_i[c]),
                                        is_wall(j) ? problem.wall_body(j) : std::size_t(j)};
      if (is_wall(j)) ++(problem.inverse_mass[side_body[1]] > 0.0 ? pistons : walls);
      for (int side = 0; side < 2; ++side) {
        const std::size_t b = side_body[side];
        // A fixed wall takes nothing (apply_impulse leaves it alone); its columns do not matter.
        if (side == 1 && is_wall(j) && !(problem.inverse_mass[b] > 0.0)) continue;
        const Eigen::Vector3d dv = problem.inverse_mass[b] * (columns.linear[side] * r);
        const Eigen::Vector3d dw = problem.inverse_inertia[b] * (columns.angular[side] * r);
        const double scale_v = problem.inverse_mass[b] * r.norm(), scale_w = problem.inverse_inertia[b] * r.norm() * 1e-3;
        EXPECT_LE((dv - v[b]).norm(), 1e-14 * scale_v) << "contact " << c << " side " << side;
        if (!is_wall(j) || side == 0)
          EXPECT_LE((dw - w[b]).norm(), 1e-14 * scale_w + 1e-300) << "contact " << c << " side " << side;
        else
          EXPECT_EQ(columns.angular[side], Eigen::Matrix3d::Zero());  // a wall does not turn
      }
    }
    EXPECT_GT(walls, 0);
    EXPECT_GT(pistons, 0);
  }
}

}  // namespace tmdem::mechanics

namespace tmdem::mechanics {

// contact_rows (ContactKinematics.h): a particle's rows of H_c^T give local_velocity's U (bias
// aside) when that particle alone moves, and are contact_columns' transpose: the linear part bit
// for bit, the angular part to round-off (the t2 row is 0 in 2D, where U has no t2 part).
TEST(ContactRows, RowsAreOneBodysLocalVelocityAndTheColumnsTransposed) {
  for (int dimension : {2, 3}) {
    ContactProblem problem = test::random_contact_problem(dimension, 5);
    std::fill(problem.bias.begin(), problem.bias.end(), 0.0);
    test::Draws d(13);
    const std::size_t bodies = problem.body_count();
    const int rows_used = dimension == 2 ? 2 : 3;
    int sides = 0;
    for (std::size_t c = 0; c < problem.size(); ++c) {
      const std::int32_t j = problem.body_j[c];
      const ContactColumns columns = contact_columns(problem, c);
      for (int side = 0; side < (is_wall(j) ? 1 : 2); ++side) {
        const std::size_t b = side == 0 ? std::size_t(problem.body_i[c]) : std::size_t(j);
        const Eigen::Matrix<double, 3, 6> rows = contact_rows(problem, c, side);
        std::vector<Eigen::Vector3d> v(bodies, Eigen::Vector3d::Zero()), w(bodies, Eigen::Vector3d::Zero());
        v[b] = d.vector(0.1, dimension);
        w[b] = d.vector(100.0, 3);
        if (dimension == 2) w[b] = Eigen::Vector3d(0.0, 0.0, w[b].z());
        Eigen::Matrix<double, 6, 1> motion;
        motion << v[b], w[b];
        const Eigen::Vector3d u = local_velocity<Eigen::Vector3d>(problem, c, v, w);
        const double scale = v[b].norm() + problem.lever_i[c] * w[b].norm() + problem.lever_j[c] * w[b].norm();
        EXPECT_LE((rows * motion - u).norm(), 1e-14 * scale) << "contact " << c << " side " << side;
        if (dimension == 2) {
          EXPECT_EQ(rows.row(2), (Eigen::Matrix<double, 1, 6>::Zero()));
        }
        const Eigen::Matrix3d linear_t = columns.linear[side].transpose(), angular_t = columns.angular[side].transpose();
        EXPECT_EQ(rows.topLeftCorner(rows_used, 3), linear_t.topRows(rows_used)) << "contact " << c;
        const double lever = side == 0 ? problem.lever_i[c] : problem.lever_j[c];
        EXPECT_LE((rows.topRightCorner(rows_used, 3) - angular_t.topRows(rows_used)).norm(), 1e-14 * lever)
            << "contact " << c << " side " << side;
        ++sides;
      }
    }
    EXPECT_GT(sides, int(problem.size()));
  }
}

}  // namespace tmdem::mechanics
