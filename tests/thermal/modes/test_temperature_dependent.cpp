// Temperature-dependent conductivity k(T) and specific heat c(T) (tables, piecewise linear):
// the table calculus, the Kirchhoff contact flow and its derivatives, a steady chain between two
// held temperatures against the exact Kirchhoff-transform solution, and the energy balance with
// C(T) (enthalpy state) to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/KirchhoffContactFlow.h"
#include "thermal/steady/SteadyStateSolver.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

PiecewiseLinearTable table(std::vector<double> x, std::vector<double> y) {
  return PiecewiseLinearTable{std::move(x), std::move(y)};
}

// Simpson's rule on each smooth piece of [a, b] (split at the table's points), independent of
// the trapezoid sums of PiecewiseLinearTable::integral.
double simpson(const PiecewiseLinearTable& t, double a, double b) {
  std::vector<double> cuts{a};
  for (double x : t.x)
    if (x > a && x < b) cuts.push_back(x);
  cuts.push_back(b);
  double sum = 0.0;
  for (std::size_t k = 1; k < cuts.size(); ++k) {
    const double lo = cuts[k - 1], hi = cuts[k];
    sum += (hi - lo) / 6.0 * (t(lo) + 4.0 * t(0.5 * (lo + hi)) + t(hi));
  }
  return sum;
}

// k(T) = k0 (1 + beta (T - T0)), exact as a two-point table between 200 and 500 K.
constexpr double kK0 = 20.0, kBeta = 2e-3, kT0 = 300.0;
double k_linear(double T) { return kK0 * (1.0 + kBeta * (T - kT0)); }
PiecewiseLinearTable k_table() { return table({200.0, 500.0}, {k_linear(200.0), k_linear(500.0)}); }
// theta(T) - theta(T0) for the linear k, and its inverse.
double theta(double T) { return kK0 * ((T - kT0) + 0.5 * kBeta * (T - kT0) * (T - kT0)); }
double theta_inverse(double value) {
  return kT0 + 2.0 * value / kK0 / (1.0 + std::sqrt(1.0 + 2.0 * kBeta * value / kK0));
}

// One material (k table, c table) for every node; H_e = 2 a_e k_ref as the bridge sets it.
ThermalNetwork tdep_chain(int n, const std::vector<double>& two_a, const PiecewiseLinearTable& k,
                          const PiecewiseLinearTable& c, double mass_kg) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  net.material_conductivity = {k};
  net.material_specific_heat = {c};
  for (int i = 0; i < n; ++i) {
    net.node_material.push_back(0);
    net.mass_kg.push_back(mass_kg);
    net.heat_capacity_J_per_K[std::size_t(i)] = mass_kg * c.y.front();
  }
  for (int e = 0; e + 1 < n; ++e) net.add_edge(e, e + 1, two_a[std::size_t(e)] * k.y.front());
  net.conductance_follows_conductivity = true;
  return net;
}

}  // namespace

TEST(TemperatureDependent, TableIntegralSlopeAndInverse) {
  const auto t = table({250.0, 400.0, 700.0}, {400.0, 520.0, 610.0});
  for (double T : {100.0, 250.0, 300.0, 400.0, 555.5, 700.0, 900.0}) {
    const double expected = simpson(t, 0.0, T);
    EXPECT_NEAR(t.integral(T), expected, 1e-13 * expected) << T;
    EXPECT_NEAR(t.inverse_integral(t.integral(T)), T, 1e-12 * T) << T;
    const double h = 1e-4;
    if (T != 250.0 && T != 400.0 && T != 700.0) {
      EXPECT_NEAR(t.slope(T), (t(T + h) - t(T - h)) / (2 * h), 1e-9) << T;
    }
  }
  EXPECT_EQ(t.slope(100.0), 0.0);  // clamped outside
  EXPECT_EQ(t.slope(800.0), 0.0);
}

TEST(TemperatureDependent, KirchhoffFlowReducesToHertzAndBalancesBothHalfSpaces) {
  const double two_a = 1e-4;
  // Constant k: the harmonic-mean Hertz law.
  const auto k1 = table({1.0}, {50.0}), k2 = table({1.0}, {1.0});
  const auto f = kirchhoff_contact_flow(two_a, k1, 400.0, k2, 300.0);
  const double H = two_a * harmonic_mean_conductivity(50.0, 1.0);
  EXPECT_NEAR(f.W, H * 100.0, 1e-12 * H * 100.0);
  EXPECT_NEAR(f.dW_dT1, H, 1e-12 * H);
  EXPECT_NEAR(f.dW_dT2, -H, 1e-12 * H);
  // Two materials with k(T): both half-spaces carry the same flow, 4a (theta_1(T1) - theta_1(Tc))
  // = 4a (theta_2(Tc) - theta_2(T2)), and the derivatives are those of the flow.
  const auto ka = table({250.0, 450.0}, {60.0, 30.0}), kb = table({250.0, 350.0, 450.0}, {2.0, 3.0, 3.5});
  for (auto [T1, T2] : {std::pair{420.0, 280.0}, std::pair{260.0, 440.0}, std::pair{330.0, 330.5}}) {
    const auto g = kirchhoff_contact_flow(two_a, ka, T1, kb, T2);
    // Spot temperature from side 1, then side 2 must carry the same flow.
    const double Tc = ka.inverse_integral(ka.integral(T1) - g.W / (2.0 * two_a));
    const double side2 = 2.0 * two_a * (kb.integral(Tc) - kb.integral(T2));
    EXPECT_NEAR(side2, g.W, 1e-9 * std::abs(g.W) + 1e-15) << T1 << " " << T2;
    const double h = 1e-3;
    const double d1 = (kirchhoff_contact_flow(two_a, ka, T1 + h, kb, T2).W -
                       kirchhoff_contact_flow(two_a, ka, T1 - h, kb, T2).W) / (2 * h);
    const double d2 = (kirchhoff_contact_flow(two_a, ka, T1, kb, T2 + h).W -
                       kirchhoff_contact_flow(two_a, ka, T1, kb, T2 - h).W) / (2 * h);
    EXPECT_NEAR(g.dW_dT1, d1, 1e-6 * std::abs(d1)) << T1 << " " << T2;
    EXPECT_NEAR(g.dW_dT2, d2, 1e-6 * std::abs(d2)) << T1 << " " << T2;
  }
}

// Six particles in a line, the ends held at 400 K and 300 K, one material with k linear in T,
// contacts of different sizes. At steady state every contact carries the same Q =
// 2a_e (theta(T_e) - theta(T_e+1)), so theta(T_k) falls linearly in sum 1/(2a): the exact
// Kirchhoff-transform solution, here inverted in closed form.
TEST(TemperatureDependent, SteadyChainMatchesTheKirchhoffTransform) {
  const int n = 6;
  const std::vector<double> two_a = {1.0e-4, 1.6e-4, 0.7e-4, 1.2e-4, 2.0e-4};
  const double T_hot = 400.0, T_cold = 300.0;
  double resistance = 0.0;  // sum 1 / (2a), 1/m
  for (double g : two_a) resistance += 1.0 / g;
  const double Q = (theta(T_hot) - theta(T_cold)) / resistance;
  std::vector<double> exact(n);
  double partial = 0.0;
  for (int k = 0; k < n; ++k) {
    exact[std::size_t(k)] = theta_inverse(theta(T_hot) - Q * partial);
    if (k + 1 < n) partial += 1.0 / two_a[std::size_t(k)];
  }
  ASSERT_NEAR(exact.back(), T_cold, 1e-9);
  // The linear-k answer differs from a constant-k chain by up to ~1 K here: a real test.
  const auto c = table({250.0, 450.0}, {400.0, 520.0});
  auto net = tdep_chain(n, two_a, k_table(), c, 3e-5);
  net.held[0] = net.held[std::size_t(n - 1)] = 1;
  std::vector<double> T0(n, 350.0);
  T0.front() = T_hot;
  T0.back() = T_cold;
  auto sys = make_system(net, {"contact_conduction"});

  const auto steady = solve_steady_state(*sys, T0);
  for (int k = 0; k < n; ++k)
    EXPECT_NEAR(steady.T_K[std::size_t(k)], exact[std::size_t(k)], 1e-9) << "particle " << k;

  double constant_k_gap = 0.0;  // the same chain with k = k(350 K) everywhere
  {
    partial = 0.0;
    for (int k = 0; k < n; ++k) {
      const double linear = T_hot - (T_hot - T_cold) * partial / resistance;
      constant_k_gap = std::max(constant_k_gap, std::abs(linear - exact[std::size_t(k)]));
      if (k + 1 < n) partial += 1.0 / two_a[std::size_t(k)];
    }
  }
  EXPECT_GT(constant_k_gap, 0.1);

  for (const char* name : {"cvode", "ida"}) {
    IntegratorSettings s;
    s.relative_tolerance = s.absolute_tolerance_K = 1e-10;
    auto integ = make_thermal_integrator(name, *sys, s);
    integ->initialize(0.0, T0, 0.0);
    integ->advance_to(2000.0);  // time constants C / H ~ 3e-5 * 400 / 2e-3 = 6 ms: long settled
    for (int k = 0; k < n; ++k)
      EXPECT_NEAR(integ->temperatures_K()[std::size_t(k)], exact[std::size_t(k)], 1e-7)
          << name << " particle " << k;
  }
}

// An insulated random network of two materials with k(T) and c(T): the enthalpy sum
// m_i int c dT is conserved to round-off by CVODE and IDA (their state is the enthalpy), while
// the temperatures move by tens of kelvin; with isothermal walls and a held particle the
// balance E_final - E_initial = boundary heat closes like the constant-property one.
TEST(TemperatureDependent, EnergyIsTheIntegralOfCAndBalances) {
  const int n = 24;
  std::mt19937_64 rng(7);
  auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53; };
  ThermalNetwork net;
  net.resize_nodes(n);
  net.material_conductivity = {table({250.0, 350.0, 500.0}, {80.0, 55.0, 40.0}),
                               table({250.0, 500.0}, {1.0, 1.6})};
  net.material_specific_heat = {table({250.0, 400.0, 500.0}, {420.0, 500.0, 540.0}),
                                table({250.0, 500.0}, {700.0, 950.0})};
  std::vector<double> T0(n);
  for (int i = 0; i < n; ++i) {
    net.node_material.push_back(i % 3 == 0 ? 1 : 0);
    net.mass_kg.push_back(1e-5 * (1.0 + uniform()));
    T0[std::size_t(i)] = 260.0 + 220.0 * uniform();
    net.heat_capacity_J_per_K[std::size_t(i)] = net.heat_capacity_at(std::size_t(i), T0[std::size_t(i)]);
  }
  for (int i = 0; i + 1 < n; ++i) net.add_edge(i, i + 1, 1e-4 * (0.5 + uniform()));
  for (int e = 0; e < 20; ++e) {
    int a = int(rng() % n), b = int(rng() % n);
    if (std::abs(a - b) < 2) continue;
    net.add_edge(std::min(a, b), std::max(a, b), 1e-4 * (0.5 + uniform()));
  }
  net.conductance_follows_conductivity = true;
  for (const char* name : {"cvode", "ida"}) {
    auto sys = make_system(net, {"contact_conduction"});
    IntegratorSettings s;
    s.relative_tolerance = s.absolute_tolerance_K = 1e-8;
    auto integ = make_thermal_integrator(name, *sys, s);
    integ->initialize(0.0, T0, 0.0);
    const double E0 = sys->thermal_energy_J(T0);
    integ->advance_to(50.0);  // several times C / H ~ 45 s
    const auto T = integ->temperatures_K();
    double spread = 0.0;
    for (std::size_t i = 0; i < T.size(); ++i) spread = std::max(spread, std::abs(T[i] - T0[i]));
    EXPECT_GT(spread, 20.0) << name;
    EXPECT_NEAR(sys->thermal_energy_J(T), E0, 1e-13 * E0) << name;
    std::printf("[ balance  ] insulated %s: max |T - T0| = %.1f K, |E - E0| / E0 = %.2e\n", name,
                spread, std::abs(sys->thermal_energy_J(T) - E0) / E0);
    EXPECT_EQ(integ->boundary_heat_J(), 0.0);
  }
  // Walls (their own material) and a held particle: heat enters and leaves.
  net.add_wall_edge(0, 480.0, 2e-4);
  net.wall_material.push_back(1);
  net.add_wall_edge(n - 1, 270.0, 3e-4);
  net.wall_material.push_back(0);
  net.held[5] = 1;
  for (const char* name : {"cvode", "ida"}) {
    auto sys = make_system(net, {"contact_conduction", "wall_conduction"});
    IntegratorSettings s;
    s.relative_tolerance = s.absolute_tolerance_K = 1e-10;
    auto integ = make_thermal_integrator(name, *sys, s);
    integ->initialize(0.0, T0, 0.0);
    const double E0 = sys->thermal_energy_J(T0);
    integ->advance_to(100.0);
    const double dE = sys->thermal_energy_J(integ->temperatures_K()) - E0;
    const double Q = integ->boundary_heat_J();
    EXPECT_GT(std::abs(Q), 1e-3 * E0) << name;
    EXPECT_NEAR(dE, Q, 1e-8 * std::max(std::abs(E0), std::abs(Q))) << name;
    std::printf("[ balance  ] %s: E0 = %.6g J, Q = %.6g J, |dE - Q| / E0 = %.2e\n", name, E0, Q,
                std::abs(dE - Q) / E0);
    EXPECT_EQ(integ->temperatures_K()[5], T0[5]) << name;
  }
}

// The refusals: the explicit update (its stability bound assumes constant C and k) and pcg
// (the Jacobian is one-sided), each naming the fix.
TEST(TemperatureDependent, ExplicitAndPcgAreRefused) {
  auto net = tdep_chain(3, {1e-4, 1e-4}, k_table(), table({1.0}, {450.0}), 1e-5);
  auto sys = make_system(net, {"contact_conduction"});
  try {
    make_thermal_integrator("explicit", *sys, {});
    ADD_FAILURE() << "explicit accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"cvode\" or \"ida\""), std::string::npos) << e.what();
  }
  IntegratorSettings s;
  s.linear_solver = LinearSolverKind::Pcg;
  try {
    make_thermal_integrator("cvode", *sys, s);
    ADD_FAILURE() << "pcg accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"klu\""), std::string::npos) << e.what();
  }
}
