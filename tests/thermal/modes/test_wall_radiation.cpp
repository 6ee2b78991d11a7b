// Radiation with walls and in enclosed beds (PairRadiationGeometry.h, ParticleRadiationMode.cpp,
// RadiationMode.cpp): a wall within pair_cutoff takes half of what the particle's neighbours
// leave open and the surroundings the rest, each at its formula with the exact Jacobian; a
// sphere enclosed between two walls settles at the mean of their fourth powers; in an enclosed
// row each sphere's view factors are scaled to sum to 1 and every pair still conserves energy.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "thermal/ThermalTestSupport.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

constexpr double kWallSigma = 5.670374419e-8;
constexpr double kWallR = 1e-3;

double wall_test_F(double gap_m) {
  const double d = 2.0 * kWallR + gap_m;
  return 0.5 * (1.0 - std::sqrt(1.0 - (kWallR / d) * (kWallR / d)));
}

double wall_test_eps(double a, double b) { return 1.0 / (1.0 / a + 1.0 / b - 1.0); }

ThermalNetwork wall_test_spheres(int n, double eps, double gap_m) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    net.heat_capacity_J_per_K[i] = 1e-2;
    net.radius_m[i] = kWallR;
    net.surface_area_m2[i] = sphere_area(kWallR);
    net.emissivity[i] = eps;
  }
  for (int i = 0; i + 1 < n; ++i) net.add_edge(i, i + 1, 0.0, gap_m, 0.0, false);
  return net;
}

void wall_test_add_wall(ThermalNetwork& net, int node, double T_K, double gap_m, double eps) {
  net.add_wall_edge(node, T_K, 0.0, -1, gap_m, 0.0, false);
  net.wall_emissivity.push_back(eps);
}

// Both radiation modes' keys, as the scene's [radiation] section gives them to each.
ModeSettings wall_test_settings(bool walls, bool surroundings, double ambient_K = 300.0) {
  ModeSettings s;
  for (const char* mode : {"radiation", "particle_radiation"}) {
    s.set(mode, "between_particles", 1.0);
    s.set(mode, "pair_cutoff", 0.5);
    s.set(mode, "walls", walls ? 1.0 : 0.0);
    s.set(mode, "surroundings", surroundings ? 1.0 : 0.0);
  }
  s.set("radiation", "ambient_temperature", ambient_K);
  return s;
}

double wall_test_p4(double T) { return T * T * T * T; }

}  // namespace

TEST(WallRadiation, WallTakesHalfOfWhatTheNeighboursLeaveOpen) {
  const double gap = 0.1 * kWallR, Ta = 300.0, Tw = 1200.0, T0 = 900.0, T1 = 700.0;
  const double eps = 0.8, eps_w = 0.6, A = sphere_area(kWallR), F = wall_test_F(gap);
  auto net = wall_test_spheres(2, eps, gap);
  wall_test_add_wall(net, 0, Tw, 0.05 * kWallR, eps_w);
  wall_test_add_wall(net, 1, Tw, 0.6 * kWallR, eps_w);  // beyond pair_cutoff: no exchange with the wall
  auto sys = make_system(net, {"radiation", "particle_radiation"}, wall_test_settings(true, true, Ta));
  const std::vector<double> T{T0, T1};
  std::vector<double> q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  const double open = 1.0 - F, scale = kWallSigma * A * wall_test_p4(Tw);
  const double pair = kWallSigma * wall_test_eps(eps, eps) * A * F * (wall_test_p4(T1) - wall_test_p4(T0));
  const double wall = kWallSigma * wall_test_eps(eps, eps_w) * A * open / 2.0 * (wall_test_p4(Tw) - wall_test_p4(T0));
  const double ambient0 = kWallSigma * eps * A * open / 2.0 * (wall_test_p4(Ta) - wall_test_p4(T0));
  const double ambient1 = kWallSigma * eps * A * open * (wall_test_p4(Ta) - wall_test_p4(T1));
  EXPECT_NEAR(q[0], pair + wall + ambient0, 1e-14 * scale);
  EXPECT_NEAR(q[1], -pair + ambient1, 1e-14 * scale);
  // Energy: what the particles gain came through the wall and from the surroundings.
  EXPECT_NEAR(boundary, wall + ambient0 + ambient1, 1e-14 * scale);
  // The exact Jacobian's diagonal: every term's -4 G T^3.
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  const double d0 = -4.0 * kWallSigma * A * std::pow(T0, 3) *
                    (wall_test_eps(eps, eps) * F + wall_test_eps(eps, eps_w) * open / 2.0 + eps * open / 2.0);
  EXPECT_NEAR(J.diagonal_W_per_K[0], d0, 1e-14 * std::abs(d0));

  // walls = false: the wall neither exchanges nor shades.
  auto no_walls = make_system(net, {"radiation", "particle_radiation"}, wall_test_settings(false, true, Ta));
  ASSERT_TRUE(no_walls->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[0], pair + kWallSigma * eps * A * open * (wall_test_p4(Ta) - wall_test_p4(T0)), 1e-14 * scale);
}

TEST(WallRadiation, TwoWallsShareTheOpenShareAndAnEnclosedSphereTakesTheirMeanFourthPower) {
  const double T_hot = 1200.0, T_cold = 800.0, eps = 0.7, eps_w = 0.9, A = sphere_area(kWallR);
  auto net = wall_test_spheres(1, eps, 0.0);
  wall_test_add_wall(net, 0, T_hot, 0.0, eps_w);
  wall_test_add_wall(net, 0, T_cold, 0.2 * kWallR, eps_w);
  const double G = kWallSigma * wall_test_eps(eps, eps_w) * A * 0.5;
  // With surroundings (the ambient mode is built only then), nothing is left for them.
  auto open = make_system(net, {"radiation", "particle_radiation"}, wall_test_settings(true, true, 300.0));
  std::vector<double> q(1);
  double boundary = 0.0;
  ASSERT_TRUE(open->heat_flow(std::vector<double>{1000.0}, q, boundary));
  EXPECT_NEAR(q[0], G * (wall_test_p4(T_hot) + wall_test_p4(T_cold) - 2.0 * wall_test_p4(1000.0)), 1e-14 * G * wall_test_p4(T_hot));
  // Enclosed, the sphere is at rest at ((T_hot^4 + T_cold^4) / 2)^(1/4) and warms or cools
  // towards it from either side.
  auto enclosed = make_system(net, {"particle_radiation"}, wall_test_settings(true, false));
  const double T_star = std::pow(0.5 * (wall_test_p4(T_hot) + wall_test_p4(T_cold)), 0.25);
  ASSERT_TRUE(enclosed->heat_flow(std::vector<double>{T_star}, q, boundary));
  EXPECT_NEAR(q[0], 0.0, 1e-13 * G * wall_test_p4(T_hot));
  ASSERT_TRUE(enclosed->heat_flow(std::vector<double>{T_star - 1.0}, q, boundary));
  EXPECT_GT(q[0], 0.0);
  ASSERT_TRUE(enclosed->heat_flow(std::vector<double>{T_star + 1.0}, q, boundary));
  EXPECT_LT(q[0], 0.0);
  // And an integrator, from 300 K, lands there.
  auto st = tight_settings("klu", 1e-9);
  st.max_temperature_K = T_hot;
  auto integ = make_thermal_integrator("cvode", *enclosed, st);
  integ->initialize(0.0, std::vector<double>{300.0}, 0.0);
  integ->advance_to(2000.0);
  EXPECT_NEAR(integ->temperatures_K()[0], T_star, 1e-4 * T_star);
}

TEST(WallRadiation, EnclosedViewFactorsSumToOneAndConserveEnergy) {
  // A row 0-1-2: the ends see one neighbour, the middle two. Scaled to sum to 1, the end's
  // view factor to the middle is 1 and the middle's to each end 1/2: G = sigma eps A 3/4.
  const double gap = 0.1 * kWallR, eps = 0.9, A = sphere_area(kWallR);
  auto net = wall_test_spheres(3, eps, gap);
  auto sys = make_system(net, {"particle_radiation"}, wall_test_settings(true, false));
  const std::vector<double> T{1100.0, 900.0, 700.0};
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  const double G = kWallSigma * wall_test_eps(eps, eps) * A * 0.75;
  EXPECT_NEAR(q[0], G * (wall_test_p4(T[1]) - wall_test_p4(T[0])), 1e-14 * G * wall_test_p4(T[0]));
  EXPECT_NEAR(q[2], G * (wall_test_p4(T[1]) - wall_test_p4(T[2])), 1e-14 * G * wall_test_p4(T[0]));
  EXPECT_NEAR(q[0] + q[1] + q[2], 0.0, 1e-15 * G * wall_test_p4(T[0]));
  EXPECT_EQ(boundary, 0.0);
  // With surroundings the same row keeps the unscaled view factors (PairFlowIsSigmaEpsFA...).
  auto open = make_system(net, {"particle_radiation"}, wall_test_settings(true, true));
  ASSERT_TRUE(open->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[0], kWallSigma * wall_test_eps(eps, eps) * A * wall_test_F(gap) * (wall_test_p4(T[1]) - wall_test_p4(T[0])),
              1e-14 * G * wall_test_p4(T[0]));
}

TEST(WallRadiation, AShadowedPairNeitherExchangesNorTakesAShare) {
  // The row 0-1-2 with an extra edge 0-2 (as a near pair round sphere 1 would be): marked
  // shadowed, the flows are the row's own; unmarked, the pair exchanges and the shares change.
  const double gap = 0.1 * kWallR, eps = 0.9;
  const std::vector<double> T{1100.0, 900.0, 700.0};
  std::vector<double> row_q(3), q(3);
  double boundary = 0.0;
  auto row = make_system(wall_test_spheres(3, eps, gap), {"particle_radiation"},
                         wall_test_settings(true, false));
  ASSERT_TRUE(row->heat_flow(T, row_q, boundary));
  for (const bool shadowed : {true, false}) {
    auto net = wall_test_spheres(3, eps, gap);
    net.add_edge(0, 2, 0.0, 0.3 * kWallR, 0.0, false);
    net.edge_shadowed = {0, 0, std::uint8_t(shadowed ? 1 : 0)};
    auto sys = make_system(net, {"particle_radiation"}, wall_test_settings(true, false));
    ASSERT_TRUE(sys->heat_flow(T, q, boundary));
    for (std::size_t i = 0; i < 3; ++i) {
      if (shadowed) EXPECT_EQ(q[i], row_q[i]) << i;
      else EXPECT_NE(q[i], row_q[i]) << i;
    }
  }
}
