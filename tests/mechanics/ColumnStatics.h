#pragma once
// A column of spheres on the floor after one step from rest, and its closed-form statics
// (each contact carries the weight above it): the heavy-on-light columns of the Gauss-Seidel
// variants' tests (test_block_gauss_seidel.cpp, test_nncg_solver.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "MechanicsTestScenes.h"

namespace tmdem::mechanics::test {

// A column of touching spheres of radius kRadius on the floor (mu = 0.3), masses bottom up,
// after one step from rest: its problem's reactions are the weights carried.
inline NscdIntegrator column(const std::vector<double>& masses_kg) {
  ParticleSet set;
  for (std::size_t k = 0; k < masses_kg.size(); ++k) {
    set.add(Eigen::Vector3d(0.0, (2.0 * k + 1.0) * kRadius, 0.0), kRadius, masses_kg[k], 0);
  }
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Eigen::Vector3d(0, -kG, 0), 3, nlgs_parameters());
  sim.step();
  return sim;
}

// Each contact of the column carries the weight of the spheres above its contact point, N s.
inline void expect_column_statics(const NscdIntegrator& sim, const std::vector<Eigen::Vector3d>& r, double relative) {
  const ContactProblem& p = sim.problem();
  const double h = sim.parameters().time_step;
  std::size_t loaded = 0;
  for (std::size_t c = 0; c < p.size(); ++c) {
    const double y_contact = sim.particles().position[p.body_i[c]].y() - p.normal[c].y() * kRadius;
    double carried = 0.0;
    for (std::size_t k = 0; k < sim.particles().size(); ++k) {
      if (sim.particles().position[k].y() > y_contact) carried += sim.particles().mass[k] * kG * h;
    }
    if (std::abs(p.normal[c].y()) < 0.5) carried = 0.0;  // not a contact of the column
    loaded += carried > 0.0 ? 1 : 0;
    EXPECT_NEAR(r[c][0], carried, relative * carried + 1e-18) << "contact " << c;
    EXPECT_LE(r[c].tail<2>().norm(), relative * carried + 1e-18) << "contact " << c;
  }
  EXPECT_EQ(loaded, sim.particles().size());  // one loaded contact under each sphere
}

// Symmetric Gauss-Seidel on a light sphere (b = 1/m_L) between a heavy one (a = 1/m_H) and the
// floor: the forward sweep contracts the error by rho^2 = b / (a + b), a forward-backward pair
// by the same (its backward half starts with the contact just visited), so about rho per
// sweep; from a cold start it needs ln(tolerance) / ln(rho) sweeps, and stops with an error
// of about tolerance / (1 - rho) of the reactions.
inline double plain_contraction(double light_kg, double heavy_kg) {
  const double a = 1.0 / heavy_kg, b = 1.0 / light_kg;
  return std::sqrt(b / (a + b));
}

}  // namespace tmdem::mechanics::test
