// The direct steady-state solver (thermal/steady/SteadyStateSolver.h) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "thermal/ThermalTestSupport.h"
#include "thermal/steady/SteadyStateSolver.h"
#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {
namespace {

using testing::chain_network;
using testing::make_system;

// A chain of unequal conductances between two held ends: the same heat Q crosses every
// resistance, Q = dT / sum(1/H), and T drops by Q / H_e across edge e.
TEST(SteadyState, SeriesChainBetweenHeldEnds) {
  const std::vector<double> H{1e-3, 4e-3, 2.5e-4, 7e-3, 1e-3};
  ThermalNetwork net;
  net.resize_nodes(H.size() + 1);
  for (auto& C : net.heat_capacity_J_per_K) C = 0.01;
  for (std::size_t e = 0; e < H.size(); ++e) net.add_edge(int(e), int(e + 1), H[e]);
  net.held.front() = net.held.back() = 1;
  const auto sys = make_system(net, {"contact_conduction"});
  std::vector<double> T0(net.node_count(), 300.0);
  T0.front() = 400.0;
  T0.back() = 250.0;
  const auto s = solve_steady_state(*sys, T0);
  double R = 0.0;
  for (double h : H) R += 1.0 / h;
  const double Q = (400.0 - 250.0) / R;
  double T = 400.0;
  for (std::size_t e = 0; e < H.size(); ++e) {
    T -= Q / H[e];
    EXPECT_NEAR(s.T_K[e + 1], T, 1e-11) << "node " << e + 1;
  }
  EXPECT_EQ(s.T_K.back(), 250.0);
  EXPECT_EQ(s.floating_particles, 0u);
  EXPECT_LE(s.newton_iterations, 3);
  EXPECT_EQ(s.factorizations, 1);  // linear: the second Newton step reuses the factors
}

// A pair touching only each other exchanges nothing with the rest: its steady temperature is
// undetermined, so it keeps its start values and is counted; the wall-fed particle reaches the
// wall temperature.
TEST(SteadyState, FloatingPairKeepsStartTemperatures) {
  ThermalNetwork net;
  net.resize_nodes(3);
  for (auto& C : net.heat_capacity_J_per_K) C = 0.01;
  net.add_edge(1, 2, 1e-3);
  net.add_wall_edge(0, 350.0, 2e-3);
  net.isothermal_walls = 1;
  const auto sys = make_system(net, {"contact_conduction", "wall_conduction"});
  const auto s = solve_steady_state(*sys, std::vector<double>{300.0, 310.0, 320.0});
  EXPECT_NEAR(s.T_K[0], 350.0, 1e-12);
  EXPECT_EQ(s.T_K[1], 310.0);
  EXPECT_EQ(s.T_K[2], 320.0);
  EXPECT_EQ(s.floating_particles, 2u);
}

// Nonlinear: one particle between a wall (H) and radiation to an ambient. Newton must reach
// H (T_w - T) = eps sigma A (T^4 - T_a^4) to round-off.
TEST(SteadyState, WallAgainstRadiationBalances) {
  ThermalNetwork net;
  net.resize_nodes(1);
  net.heat_capacity_J_per_K[0] = 0.01;
  net.surface_area_m2[0] = 1.2566e-5;
  net.emissivity[0] = 0.8;
  const double H = 1e-4, Tw = 900.0, Ta = 300.0;
  net.add_wall_edge(0, Tw, H);
  net.isothermal_walls = 1;
  ModeSettings settings;
  settings.set("radiation", "ambient_temperature", Ta);
  const auto sys = make_system(net, {"wall_conduction", "radiation"}, settings);
  const auto s = solve_steady_state(*sys, std::vector<double>{300.0});
  const double T = s.T_K[0];
  const double sigma = 5.670374419e-8;
  const double wall = H * (Tw - T), rad = 0.8 * sigma * 1.2566e-5 * (std::pow(T, 4) - std::pow(Ta, 4));
  EXPECT_NEAR(wall, rad, 1e-12 * wall);
  EXPECT_GT(s.newton_iterations, 2);  // a genuinely nonlinear solve
  EXPECT_GT(T, Ta);
  EXPECT_LT(T, Tw);
}

// Free particles with no path to any held node or wall at all: everything floats, nothing is
// solved, no failure.
TEST(SteadyState, NothingAnchoredIsNotAFailure) {
  const auto sys = make_system(chain_network(4, 0.01, 1e-3), {"contact_conduction"});
  const std::vector<double> T0{300.0, 301.0, 302.0, 303.0};
  const auto s = solve_steady_state(*sys, T0);
  EXPECT_EQ(s.T_K, T0);
  EXPECT_EQ(s.floating_particles, 4u);
}

}  // namespace
}  // namespace tmdem::thermal
