// The energy balance E_final - E_initial = Q (Q: boundary heat from the integrator) on a
// network far from equilibrium with every mode on, for every integrator; through restarts,
// stop-at-each-time and a restart offset; and a control showing the check fails when a mode
// does not report the heat it brings in.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "thermal/ThermalTestSupport.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// 40 particles, ~100 random contacts, conductances over four decades, capacities over two;
// isothermal walls at 450 K (3 particles) and 280 K (3 particles); convection to a 300 K fluid;
// radiation to 350 K surroundings; sources on 4 particles; 2 held particles (one of them with
// a wall, a source and a free neighbour, which must all stay out of Q).
struct MixedScene {
  ThermalNetwork net;
  ModeSettings ms;
  std::vector<double> T0;
};

MixedScene mixed_scene() {
  MixedScene s;
  const int n = 40;
  std::mt19937_64 rng(2024);
  auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53; };
  s.net.resize_nodes(n);
  for (int i = 0; i < n; ++i) {
    s.net.heat_capacity_J_per_K[i] = 1e-3 * std::pow(10.0, 2.0 * uniform());
    s.net.surface_area_m2[i] = sphere_area(1e-3 * (0.5 + uniform()));
    s.net.emissivity[i] = uniform();
  }
  std::set<std::pair<int, int>> used;
  for (int i = 0; i + 1 < n; ++i) {  // a spanning chain, then random extra contacts
    used.insert({i, i + 1});
    s.net.add_edge(i, i + 1, 1e-5 * std::pow(10.0, 4.0 * uniform()));
  }
  while (s.net.edge_count() < 100) {
    int a = int(rng() % n), b = int(rng() % n);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (!used.insert({a, b}).second) continue;
    s.net.add_edge(a, b, 1e-5 * std::pow(10.0, 4.0 * uniform()));
  }
  for (int i : {0, 1, 7}) s.net.add_wall_edge(i, 450.0, 5e-4);
  for (int i : {38, 39, 20}) s.net.add_wall_edge(i, 280.0, 3e-4);
  for (int i : {5, 11, 25, 20}) s.net.heat_source_W[i] = 2e-3;
  s.net.held[20] = 1;  // wall, source and free neighbours: none of it may count in Q
  s.net.held[31] = 1;
  s.ms.set("convection", "coefficient", 20.0);
  s.ms.set("convection", "fluid_temperature", 300.0);
  s.ms.set("radiation", "ambient_temperature", 350.0);
  s.T0.resize(n);
  for (auto& T : s.T0) T = 250.0 + 300.0 * uniform();
  s.T0[20] = 500.0;
  s.T0[31] = 260.0;
  return s;
}

const std::vector<std::string> kEveryMode{"contact_conduction", "wall_conduction", "convection",
                                         "radiation", "heat_source"};

class BalanceTest : public ::testing::TestWithParam<IntegratorCase> {};

std::string balance_param_name(const ::testing::TestParamInfo<IntegratorCase>& info) {
  return case_name(info.param);
}

// Explicit: 0.9 of the bound is ~0.01 s on this network, so 200 s is ~2e4 steps.
constexpr double kEndTime = 200.0;

}  // namespace

TEST_P(BalanceTest, MixedSceneClosesAtEveryOutput) {
  const auto [integrator, solver] = GetParam();
  auto scene = mixed_scene();
  auto sys = make_system(scene.net, kEveryMode, scene.ms);
  auto integ = make_thermal_integrator(integrator, *sys, tight_settings(solver));
  integ->initialize(0.0, scene.T0, 0.0);
  const double E0 = sys->thermal_energy_J(scene.T0);
  const double t_end = kEndTime;
  double worst = 0.0;
  for (int k = 1; k <= 10; ++k) {
    integ->advance_to(t_end * k / 10);
    const double err = balance_error_rel(*sys, scene.T0, *integ);
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-8) << "t = " << integ->time_s();
    EXPECT_NEAR(integ->temperatures_K()[20], 500.0, solver != "klu" ? 1e-12 : 0.0)
        << "held particle moved";
  }
  // Far from equilibrium: the boundary heat is a sizeable part of the energy, so the balance
  // is a real test of Q (E moved by several percent).
  const double dE = sys->thermal_energy_J(integ->temperatures_K()) - E0;
  EXPECT_GT(std::abs(integ->boundary_heat_J()), 1e-2 * std::abs(E0));
  EXPECT_GT(std::abs(dE), 1e-2 * std::abs(E0));
  std::printf("[ balance  ] MixedScene %-10s worst balance_error_rel = %.2e  (E0 = %.4g J, Q = %.4g J, "
              "steps %ld)\n",
              case_name(GetParam()).c_str(), worst, E0, integ->boundary_heat_J(), integ->stats().steps);
}

TEST_P(BalanceTest, ClosesThroughRestartsStopTimesAndACheckpointOffset) {
  // stop_at_each_time + restart() every output + a non-zero starting boundary heat (restart
  // from a checkpoint): E_final - E_initial = Q - Q0.
  const auto [integrator, solver] = GetParam();
  auto scene = mixed_scene();
  auto sys = make_system(scene.net, kEveryMode, scene.ms);
  auto s = tight_settings(solver);
  s.stop_at_each_time = true;
  auto integ = make_thermal_integrator(integrator, *sys, s);
  const double Q0 = 1.25;
  integ->initialize(0.0, scene.T0, Q0);
  const double E0 = sys->thermal_energy_J(scene.T0);
  const double t_end = kEndTime;
  for (int k = 1; k <= 10; ++k) {
    integ->advance_to(t_end * k / 10);
    EXPECT_DOUBLE_EQ(integ->time_s(), t_end * k / 10);
    const double err = balance_error_rel(E0, sys->thermal_energy_J(integ->temperatures_K()),
                                         integ->boundary_heat_J() - Q0);
    EXPECT_LT(err, 1e-8) << "t = " << integ->time_s();
    integ->restart();
  }
  if (integrator != "explicit") { EXPECT_EQ(integ->stats().reinitializations, 10); }
}

TEST_P(BalanceTest, DefaultTolerancesAreReported) {
  // At the default tolerances (1e-6) the balance is looser; the figure is reported here and
  // bounded by 1e-6 (a quadrature that missed a mode would be off by percent, see the control).
  const auto [integrator, solver] = GetParam();
  auto scene = mixed_scene();
  auto sys = make_system(scene.net, kEveryMode, scene.ms);
  IntegratorSettings s;
  s.linear_solver = solver_kind(solver);
  auto integ = make_thermal_integrator(integrator, *sys, s);
  integ->initialize(0.0, scene.T0, 0.0);
  integ->advance_to(kEndTime);
  const double err = balance_error_rel(*sys, scene.T0, *integ);
  std::printf("[ balance  ] MixedScene default tolerances %-10s balance_error_rel = %.2e (steps %ld)\n",
              case_name(GetParam()).c_str(), err, integ->stats().steps);
  EXPECT_LT(err, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Integrators, BalanceTest, ::testing::ValuesIn(all_integrator_cases()),
                         balance_param_name);

namespace {

// Convection that forgets to report its power as boundary heat.
class LeakyConvection final : public HeatTransferMode {
 public:
  std::string_view name() const override { return "leaky_convection"; }
  bool add_heat_flow(const ThermalNetwork& net, std::span<const double> T, std::span<double> q,
                     double&) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) q[i] += 1e-3 * (400.0 - T[i]);
    return true;
  }
  void add_jacobian(const ThermalNetwork& net, std::span<const double>,
                    JacobianView J) const override {
    for (std::size_t i = 0; i < net.node_count(); ++i) J.diagonal_W_per_K[i] -= 1e-3;
  }
};

}  // namespace

TEST_P(BalanceTest, ControlAModeThatHidesItsHeatIsCaught) {
  const auto [integrator, solver] = GetParam();
  auto net = chain_network(5, 1e-2, 1e-3);
  std::vector<std::unique_ptr<HeatTransferMode>> modes;
  modes.push_back(make_heat_transfer_mode("contact_conduction", {}));
  modes.push_back(std::make_unique<LeakyConvection>());
  ThermalSystem sys(net, std::move(modes));
  const std::vector<double> T0(5, 300.0);
  auto integ = make_thermal_integrator(integrator, sys, tight_settings(solver));
  integ->initialize(0.0, T0, 0.0);
  integ->advance_to(10.0);
  EXPECT_EQ(integ->boundary_heat_J(), 0.0);
  EXPECT_GT(balance_error_rel(sys, T0, *integ), 1e-3);
}

// A linear network (no radiation: an exact, constant Jacobian) with the direct solver: the
// boundary-heat quadrature is then the energy of the state's step by construction, and the
// balance closes to round-off at every tolerance, not just at tight ones. Two defects broke this
// (examples/column_in_air.toml, found by logging E - E0 - Q after every CVODES step): at an order
// increase CVODES built the quadrature's new history column from the previous step's correction
// (quadrature error control off), and steps taken with a Newton matrix of an older gamma (or c_j)
// stopped short of the solution, so the quadrature saw another state than the energy. Without the
// fixes this scene's worst error over these tolerances was 2.3e-5 (cvode, quadrature error control
// off) and 2.6e-7 (cvode) / 3.1e-5 (ida) with the default Newton-matrix updates.
class LinearBalanceTest : public ::testing::TestWithParam<std::string> {};

TEST_P(LinearBalanceTest, ClosesToRoundOffAtEveryTolerance) {
  const std::string integrator = GetParam();
  auto scene = mixed_scene();
  auto sys = make_system(scene.net, {"contact_conduction", "wall_conduction", "convection",
                                     "heat_source"}, scene.ms);
  double worst = 0.0;
  for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    IntegratorSettings s;
    s.linear_solver = LinearSolverKind::Klu;
    s.relative_tolerance = rtol;
    s.absolute_tolerance_K = rtol;
    auto integ = make_thermal_integrator(integrator, *sys, s);
    integ->initialize(0.0, scene.T0, 0.0);
    for (int k = 1; k <= 20; ++k) {
      integ->advance_to(kEndTime * k / 20);
      const double err = balance_error_rel(*sys, scene.T0, *integ);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-12) << "rtol " << rtol << ", t = " << integ->time_s();
    }
    EXPECT_GT(std::abs(integ->boundary_heat_J()), 1e-2 * std::abs(sys->thermal_energy_J(scene.T0)));
  }
  std::printf("[ balance  ] linear MixedScene %s, rtol 1e-3..1e-8: worst balance_error_rel %.2e\n",
              integrator.c_str(), worst);
}

INSTANTIATE_TEST_SUITE_P(Integrators, LinearBalanceTest, ::testing::Values("cvode", "ida"));
