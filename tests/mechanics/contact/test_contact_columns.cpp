// contact_columns (ContactKinematics.h): the columns of M^-1 H_c at unit mobilities, scaled by a
// body's inverse mass and inertia, are what apply_impulse does to that body for any local impulse
// (particles on both sides, a fixed floor, a piston), to round-off.
#include <gtest/gtest.h>

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
