// Heat-transfer modes against exact answers, for every integrator: convection and radiation of
// one particle (closed forms), a chain between two isothermal walls (steady profile), a chain
// with a held particle and a source (matrix exponential), a field at equilibrium with every
// mode on. Every run also checks that the energy balance closes (contract formula, below 1e-8
// at tolerance 1e-10; thermal/modes/ModeTestSupport.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/ModeTestSupport.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;
using namespace tmdem::thermal::mode_test;

namespace {

std::string param_name(const ::testing::TestParamInfo<IntegratorCase>& info) {
  return case_name(info.param);
}

}  // namespace

// ---- convection ---------------------------------------------------------------------------

TEST_P(ModeTest, ConvectionCoolsOneParticleExponentially) {
  const auto [integrator, solver] = GetParam();
  // A 1 mm steel sphere in a fluid: k = h A / C = 0.0837 1/s.
  const double r = 1e-3, C = 7800.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r * 460.0;
  const double A = sphere_area(r), h = 100.0, Tf = 293.15, T0 = 573.15;
  const double k = h * A / C;
  ModeSettings ms;
  ms.set("convection", "coefficient", h);
  ms.set("convection", "fluid_temperature", Tf);
  auto sys = make_system(single_particle(C, A), {"convection"}, ms);
  auto s = tight_settings(solver);
  const double step = 1.0 / 64.0;  // a power of two: t accumulates without rounding
  s.explicit_step_s = step;
  auto integ = make_thermal_integrator(integrator, *sys, s);
  const std::vector<double> T0v{T0};
  integ->initialize(0.0, T0v, 0.0);
  for (double t : {1.0, 2.0, 5.0, 10.0, 20.0, 40.0, 60.0}) {
    integ->advance_to(t);
    const double T = integ->temperatures_K()[0];
    const double exact = Tf + (T0 - Tf) * std::exp(-k * t);
    if (integrator == "explicit") {
      // Forward Euler's own exact answer, (1 - k h)^n, to round-off ...
      const double n = t / step;
      EXPECT_NEAR(T, Tf + (T0 - Tf) * std::pow(1.0 - k * step, n), 1e-9) << "t = " << t;
      // ... and its distance from the ODE: dT0 [(1 - kh)^n - e^{-kt}] ~ -dT0 e^{-kt} kt kh / 2,
      // at most dT0 kh / (2e) over all t.
      EXPECT_NEAR(T, exact, (T0 - Tf) * k * step / (2.0 * std::numbers::e) * 1.01) << "t = " << t;
      EXPECT_GT(std::abs(T - exact), 0.5 * (T0 - Tf) * std::exp(-k * t) * k * t * k * step / 2.0);
    } else {
      EXPECT_NEAR(T, exact, 1e-6) << "t = " << t;
    }
    expect_balance(*sys, T0v, *integ, test_name());
  }
  if (integrator == "explicit") { EXPECT_EQ(integ->stats().steps, 60 * 64); }
}

// ---- radiation ----------------------------------------------------------------------------

TEST(RadiationClosedForm, AgreesWithQuadratureOfTheOde) {
  // The reference itself: t(T) from the closed form against Simpson's rule on
  // int dT / (k (T^4 - a^4)), cooling, heating and a = 0.
  const double k = 0.8 * kStefanBoltzmann * sphere_area(1e-3) / 1e-3;
  struct Case { double T0, T, Ta; };
  for (const auto& c : {Case{1000.0, 500.0, 300.0}, Case{1000.0, 310.0, 300.0},
                        Case{250.0, 590.0, 600.0}, Case{1000.0, 400.0, 0.0}}) {
    const double closed = radiation_time_to_reach(c.T0, c.T, k, c.Ta);
    const double quad = radiation_time_by_quadrature(c.T0, c.T, k, c.Ta, 200000);
    EXPECT_GT(closed, 0.0);
    EXPECT_NEAR(closed, quad, 1e-9 * closed) << c.T0 << " -> " << c.T << " (Ta " << c.Ta << ")";
    // Bisection inverts it.
    EXPECT_NEAR(radiation_temperature(c.T0, closed, k, c.Ta), c.T, 1e-9 * c.T);
  }
}

struct RadiationCase {
  double T0, Ta;
  const char* label;
};

class RadiationTest : public ::testing::TestWithParam<std::tuple<IntegratorCase, RadiationCase>> {};

TEST_P(RadiationTest, OneParticleFollowsTheClosedForm) {
  const auto [icase, rcase] = GetParam();
  const auto [integrator, solver] = icase;
  const double C = 1e-3, eps = 0.8, A = sphere_area(1e-3);
  const double k = eps * kStefanBoltzmann * A / C;
  ModeSettings ms;
  ms.set("radiation", "ambient_temperature", rcase.Ta);
  auto sys = make_system(single_particle(C, A, eps), {"radiation"}, ms);
  const std::vector<double> T0v{rcase.T0};
  const std::vector<double> times{0.5, 1.0, 2.0, 4.0, 8.0};

  if (integrator != "explicit") {
    auto integ = make_thermal_integrator(integrator, *sys, tight_settings(solver));
    integ->initialize(0.0, T0v, 0.0);
    for (double t : times) {
      integ->advance_to(t);
      const double T = integ->temperatures_K()[0];
      const double exact = radiation_temperature(rcase.T0, t, k, rcase.Ta);
      EXPECT_NEAR(T, exact, 1e-8 * exact) << rcase.label << ", t = " << t;  // measured 1.2e-9
      expect_balance(*sys, T0v, *integ, test_name());
    }
    return;
  }
  // Forward Euler: first order, so the error at the end halves with the step.
  const double rate = 4.0 * k * std::pow(std::max(rcase.T0, rcase.Ta), 3);  // largest |dq/dT|/C
  double previous = 0.0;
  for (double step : {1e-3 / rate, 0.5e-3 / rate}) {
    auto s = tight_settings(solver);
    s.explicit_step_s = step;
    auto integ = make_thermal_integrator(integrator, *sys, s);
    integ->initialize(0.0, T0v, 0.0);
    double worst = 0.0;
    for (double t : times) {
      integ->advance_to(t);
      const double exact = radiation_temperature(rcase.T0, t, k, rcase.Ta);
      worst = std::max(worst, std::abs(integ->temperatures_K()[0] - exact));
      expect_balance(*sys, T0v, *integ, test_name());
    }
    // Steps of 1e-3 of the fastest time scale: measured 0.6e-4 of the temperature change.
    EXPECT_LT(worst, 2e-4 * std::abs(rcase.T0 - rcase.Ta)) << rcase.label << ", step " << step;
    if (previous > 0.0) { EXPECT_NEAR(previous / worst, 2.0, 0.1) << rcase.label; }
    previous = worst;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, RadiationTest,
    ::testing::Combine(::testing::ValuesIn(all_integrator_cases()),
                       ::testing::Values(RadiationCase{1000.0, 300.0, "cooling"},
                                         RadiationCase{1000.0, 0.0, "cooling_to_0K"},
                                         RadiationCase{250.0, 600.0, "heating"})),
    [](const auto& info) {
      return case_name(std::get<0>(info.param)) + "_" + std::get<1>(info.param).label;
    });

// ---- chain between two isothermal walls ---------------------------------------------------

TEST_P(ModeTest, ChainBetweenIsothermalWallsReachesTheSteadyProfile) {
  // Series resistances wall - 0 - 1 - ... - (N-1) - wall: at steady state the same flux q
  // crosses each, T_i = T_L - q sum_{k<=i} 1/H_k, q = (T_L - T_R) / sum_k 1/H_k. For equal
  // conductances that is linear: T_i = T_L + (T_R - T_L) (i + 1) / (N + 1).
  const auto [integrator, solver] = GetParam();
  const int N = 10;
  const double TL = 400.0, TR = 300.0;
  for (bool equal : {true, false}) {
    std::vector<double> H(N + 1);  // H[0]: left wall, H[k]: (k-1, k), H[N]: right wall
    for (int k = 0; k <= N; ++k) H[k] = equal ? 1e-3 : 1e-3 * (1.0 + 0.5 * std::sin(1.7 * k));
    ThermalNetwork net;
    net.resize_nodes(N);
    for (int i = 0; i < N; ++i) net.heat_capacity_J_per_K[i] = 1e-3 * (1.0 + 0.05 * i);
    for (int i = 0; i + 1 < N; ++i) net.add_edge(i, i + 1, H[i + 1]);
    net.add_wall_edge(0, TL, H[0]);
    net.add_wall_edge(N - 1, TR, H[N]);
    auto sys = make_system(net, {"contact_conduction", "wall_conduction"});
    std::vector<double> T0(N);
    for (int i = 0; i < N; ++i) T0[i] = 320.0 + 9.0 * ((3 * i) % 7);
    auto integ = make_thermal_integrator(integrator, *sys, tight_settings(solver));
    integ->initialize(0.0, T0, 0.0);
    integ->advance_to(2000.0);  // slowest mode ~0.04 1/s: e^-80
    double R = 0.0;
    for (double h : H) R += 1.0 / h;
    const double q = (TL - TR) / R;
    double R_to_i = 0.0;
    for (int i = 0; i < N; ++i) {
      R_to_i += 1.0 / H[i];
      const double exact = equal ? TL + (TR - TL) * (i + 1) / (N + 1.0) : TL - q * R_to_i;
      EXPECT_NEAR(integ->temperatures_K()[i], exact, 1e-8) << (equal ? "equal" : "unequal")
                                                           << " conductances, node " << i;
    }
    expect_balance(*sys, T0, *integ, test_name() + (equal ? " equal H" : " unequal H"));
  }
}

// ---- held particle and heat source --------------------------------------------------------

namespace {
// A chain of n with unequal capacities (1 mJ/K rising 10% a node), 0.2 mW/K links, node `held`
// held, 5 mW into the last node.
ThermalNetwork held_and_source_chain(int n, int held) {
  auto net = chain_network(n, 1e-3, 2e-4);
  for (int i = 0; i < n; ++i) net.heat_capacity_J_per_K[i] = 1e-3 * (1.0 + 0.1 * i);
  net.held[held] = 1;
  net.heat_source_W[n - 1] = 5e-3;
  return net;
}
}  // namespace

TEST(HeldAndSource, ImplicitIntegratorsAgreeWithTheMatrixExponential) {
  // Chain of 8 with unequal capacities; node 3 held at 360 K; 5 mW into the last node. Its heat
  // flows through nodes 4..6 into the held one (a reservoir); nodes 0..2 relax towards 360 K.
  const int N = 8, held = 3;
  const auto net = held_and_source_chain(N, held);
  auto sys = make_system(net, {"contact_conduction", "heat_source"});
  std::vector<double> T0(N, 300.0);
  T0[held] = 360.0;
  T0[1] = 310.0;
  const auto affine = affine_system(net, {}, false);
  std::vector<std::vector<double>> finals;
  for (const auto& [integrator, solver] : all_integrator_cases()) {
    if (integrator == "explicit") continue;
    SCOPED_TRACE(integrator + "/" + solver);
    auto integ = make_thermal_integrator(integrator, *sys, tight_settings(solver));
    integ->initialize(0.0, T0, 0.0);
    for (double t : {1.0, 5.0, 20.0, 50.0, 200.0}) {
      integ->advance_to(t);
      const auto T = integ->temperatures_K();
      EXPECT_LT(max_abs_error(T, exact_temperatures(affine, T0, t)), 2e-6) << "t = " << t;
      EXPECT_NEAR(T[held], 360.0, solver != "klu" ? 1e-12 : 0.0) << "held particle moved";
      expect_balance(*sys, T0, *integ, "HeldAndSource " + integrator + "_" + solver);
    }
    // Heat actually moved: the source raised the last node well above the reservoir.
    EXPECT_GT(integ->temperatures_K()[N - 1], 400.0);
    EXPECT_GT(integ->boundary_heat_J(), 0.1);
    finals.emplace_back(integ->temperatures_K().begin(), integ->temperatures_K().end());
  }
  ASSERT_EQ(finals.size(), 6u);
  for (std::size_t c = 1; c < finals.size(); ++c)
    for (int i = 0; i < N; ++i) EXPECT_NEAR(finals[c][i], finals[0][i], 5e-7) << "case " << c;
}

TEST(HeldAndSource, ExplicitAgreesWithTheMatrixExponential) {
  const int N = 8, held = 3;
  const auto net = held_and_source_chain(N, held);
  auto sys = make_system(net, {"contact_conduction", "heat_source"});
  std::vector<double> T0(N, 300.0);
  T0[held] = 360.0;
  auto s = tight_settings("klu");
  s.explicit_step_s = 1.0 / 1024.0;
  auto integ = make_thermal_integrator("explicit", *sys, s);
  integ->initialize(0.0, T0, 0.0);
  integ->advance_to(50.0);
  // First order at h = 1e-3 s against rates of ~0.4 1/s: measured 4.2e-4 K.
  EXPECT_LT(max_abs_error(integ->temperatures_K(), exact_temperatures(affine_system(net, {}, false), T0, 50.0)),
            1e-3);
  EXPECT_EQ(integ->temperatures_K()[held], 360.0);
  expect_balance(*sys, T0, *integ, test_name());
}

// ---- equilibrium with every mode on -------------------------------------------------------

namespace {

// Six particles with different capacities, areas and emissivities; walls on two of them; one
// held; every mode on. All temperatures (particles, walls, fluid, surroundings) are `T_eq`
// unless overridden.
struct EquilibriumScene {
  ThermalNetwork net;
  ModeSettings ms;
  std::vector<double> T0;
};

EquilibriumScene equilibrium_scene(double T_eq) {
  EquilibriumScene s;
  const int n = 6;
  s.net.resize_nodes(n);
  for (int i = 0; i < n; ++i) {
    s.net.heat_capacity_J_per_K[i] = 1e-3 * (1.0 + 0.7 * i);
    s.net.surface_area_m2[i] = sphere_area(1e-3 * (1.0 + 0.1 * i));
    s.net.emissivity[i] = 0.3 + 0.1 * i;
  }
  for (auto [a, b] : {std::pair{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 3}, {1, 5}})
    s.net.add_edge(a, b, 1e-4 * (1 + a + b));
  s.net.add_wall_edge(0, T_eq, 3e-4);
  s.net.add_wall_edge(5, T_eq, 2e-4);
  s.net.held[2] = 1;
  s.ms.set("convection", "coefficient", 50.0);
  s.ms.set("convection", "fluid_temperature", T_eq);
  s.ms.set("radiation", "ambient_temperature", T_eq);
  s.T0.assign(n, T_eq);
  return s;
}

const std::vector<std::string> kAllModes{"contact_conduction", "wall_conduction", "convection",
                                         "radiation", "heat_source"};

}  // namespace

TEST_P(ModeTest, EqualTemperaturesEverywhereMoveNoHeat) {
  const auto [integrator, solver] = GetParam();
  const double T_eq = 317.3;
  auto scene = equilibrium_scene(T_eq);
  auto sys = make_system(scene.net, kAllModes, scene.ms);
  auto integ = make_thermal_integrator(integrator, *sys, tight_settings(solver));
  integ->initialize(0.0, scene.T0, 0.0);
  integ->advance_to(integrator == "explicit" ? 5.0 : 500.0);
  // pcg integrates sqrt(C) T: a temperature comes back through one division (an ulp or two).
  for (double T : integ->temperatures_K()) EXPECT_NEAR(T, T_eq, solver != "klu" ? 1e-12 : 0.0);
  EXPECT_NEAR(integ->boundary_heat_J(), 0.0, solver != "klu" ? 1e-14 : 0.0);
  expect_balance(*sys, scene.T0, *integ, test_name());
}

TEST(Equilibrium, EachBoundaryTemperatureIsWiredIn) {
  // Control for the test above: lifting any one of the outside temperatures (wall, fluid,
  // surroundings) or switching on one source warms the free particles, so every mode takes part.
  const double T_eq = 317.3;
  struct Lift {
    const char* what;
    void (*apply)(EquilibriumScene&);
  };
  const Lift lifts[] = {
      {"wall", [](EquilibriumScene& s) { s.net.wall_temperature_K[1] += 10.0; }},
      {"fluid", [](EquilibriumScene& s) { s.ms.set("convection", "fluid_temperature", *s.ms.find("convection", "fluid_temperature") + 10.0); }},
      {"surroundings", [](EquilibriumScene& s) { s.ms.set("radiation", "ambient_temperature", *s.ms.find("radiation", "ambient_temperature") + 10.0); }},
      {"source", [](EquilibriumScene& s) { s.net.heat_source_W[4] = 1e-3; }},
  };
  for (const auto& lift : lifts) {
    auto scene = equilibrium_scene(T_eq);
    lift.apply(scene);
    auto sys = make_system(scene.net, kAllModes, scene.ms);
    auto integ = make_thermal_integrator("cvode", *sys, tight_settings("klu"));
    integ->initialize(0.0, scene.T0, 0.0);
    integ->advance_to(50.0);
    EXPECT_GT(integ->temperatures_K()[4], T_eq + 1e-3) << lift.what;
    EXPECT_EQ(integ->temperatures_K()[2], T_eq) << lift.what << ": held particle moved";
    EXPECT_GT(integ->boundary_heat_J(), 1e-6) << lift.what;
    expect_balance(*sys, scene.T0, *integ, std::string("Equilibrium lifted ") + lift.what);
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, ModeTest, ::testing::ValuesIn(all_integrator_cases()),
                         param_name);
