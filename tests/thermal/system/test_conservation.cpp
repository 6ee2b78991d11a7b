// Conservation, isolation, uniform fields and the maximum principle, for every integrator.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "thermal/ThermalTestSupport.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// A random network whose conductances span 1e-12 to 1e3 W/K (log-uniform), plus one isolated
// node (the last one).
ThermalNetwork random_network(int n, int edges, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53; };
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  for (int i = 0; i < n; ++i) net.heat_capacity_J_per_K[i] = std::pow(10.0, -4.0 + 3.0 * uniform());
  std::set<std::pair<int, int>> used;
  while (int(net.edge_count()) < edges) {
    int a = int(rng() % std::uint64_t(n - 1)), b = int(rng() % std::uint64_t(n - 1));
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (!used.insert({a, b}).second) continue;
    net.add_edge(a, b, std::pow(10.0, -12.0 + 15.0 * uniform()));
  }
  return net;
}

class ConservationTest : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

}  // namespace

TEST_P(ConservationTest, RandomStiffNetworkKeepsEnergyAndRange) {
  const auto [integrator, solver] = GetParam();
  const int n = 200;
  const auto net = random_network(n, 600, 42);
  auto sys = make_system(net, {"contact_conduction"});
  std::mt19937_64 rng(7);
  std::vector<double> T0(n);
  for (auto& T : T0) T = 280.0 + double(rng() % 1000) * 0.1;  // 280 .. 380 K
  T0[n - 1] = 345.678;
  const double lo = *std::min_element(T0.begin(), T0.end());
  const double hi = *std::max_element(T0.begin(), T0.end());
  IntegratorSettings s;
  s.linear_solver = solver_kind(solver);
  s.relative_tolerance = 1e-8;
  s.absolute_tolerance_K = 1e-8;
  auto integ = make_thermal_integrator(integrator, *sys, s);
  integ->initialize(0.0, T0, 0.0);
  const double E0 = sys->thermal_energy_J(T0);
  const double t_end = integrator == "explicit" ? 1e-6 : 1e3;  // explicit: bound ~1e-10 s
  for (int k = 1; k <= 10; ++k) {
    integ->advance_to(t_end * k / 10);
    const auto T = integ->temperatures_K();
    // A direct (KLU) Newton correction preserves sum C_i T_i to round-off; CG only to its
    // linear tolerance (measured 3e-9 relative at rtol 1e-8).
    const double tol = solver != "klu" ? 1e-8 : 1e-12;
    EXPECT_NEAR(sys->thermal_energy_J(T), E0, tol * std::abs(E0)) << "t = " << integ->time_s();
    // pcg integrates sqrt(C) T: the isolated node comes back through one division (1 ulp).
    EXPECT_NEAR(T[n - 1], 345.678, solver != "klu" ? 1e-12 : 0.0) << "isolated node moved";
    for (double Ti : T) {
      ASSERT_TRUE(std::isfinite(Ti));
      ASSERT_GE(Ti, lo - 1e-6);
      ASSERT_LE(Ti, hi + 1e-6);
    }
  }
  EXPECT_EQ(integ->boundary_heat_J(), 0.0);
}

TEST_P(ConservationTest, UniformFieldStaysUniform) {
  const auto [integrator, solver] = GetParam();
  const auto net = random_network(50, 120, 3);
  auto sys = make_system(net, {"contact_conduction"});
  IntegratorSettings s;
  s.linear_solver = solver_kind(solver);
  auto integ = make_thermal_integrator(integrator, *sys, s);
  integ->initialize(0.0, std::vector<double>(50, 321.0), 0.0);
  integ->advance_to(integrator == "explicit" ? 1e-7 : 100.0);
  // Direct solves keep it to round-off; CG moves it by its linear tolerance (6e-10 K measured).
  for (double T : integ->temperatures_K()) EXPECT_NEAR(T, 321.0, solver != "klu" ? 1e-8 : 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Integrators, ConservationTest,
                         ::testing::Values(std::make_tuple("cvode", "klu"),
                                           std::make_tuple("cvode", "pcg"),
                                           std::make_tuple("cvode", "amg"),
                                           std::make_tuple("ida", "klu"),
                                           std::make_tuple("ida", "pcg"),
                                           std::make_tuple("ida", "amg"),
                                           std::make_tuple("explicit", "klu")));

TEST(Pattern, ShapeChangeIsReanalysedAndValuesOnlyChangeIsNot) {
  auto sys = make_system(chain_network(6, 1e-3, 1e-4), {"contact_conduction"});
  IntegratorSettings s;
  s.stop_at_each_time = true;
  auto integ = make_thermal_integrator("cvode", *sys, s);
  std::vector<double> T0{400, 300, 300, 300, 300, 300};
  integ->initialize(0.0, T0, 0.0);
  integ->advance_to(1.0);
  // Same edges, new values: no re-initialisation.
  auto edges = sys->network();
  for (auto& h : edges.edge_conductance_W_per_K) h *= 2.0;
  sys->replace_edges(edges);
  integ->advance_to(2.0);
  EXPECT_EQ(integ->stats().reinitializations, 0);
  // A new contact (0, 5): re-analysed once, and energy is still conserved.
  edges.add_edge(0, 5, 3e-4);
  sys->replace_edges(edges);
  integ->advance_to(3.0);
  EXPECT_EQ(integ->stats().reinitializations, 1);
  EXPECT_EQ(integ->boundary_heat_J(), 0.0);  // regression: was NaN after a re-initialisation
  integ->advance_to(50.0);
  EXPECT_EQ(integ->stats().reinitializations, 1);
  EXPECT_NEAR(sys->thermal_energy_J(integ->temperatures_K()), sys->thermal_energy_J(T0), 1e-12 * 2);
  EXPECT_GT(integ->stats().steps, 0);
}
