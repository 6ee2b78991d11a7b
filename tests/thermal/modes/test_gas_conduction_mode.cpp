// The gas_conduction mode on a network: its flows are the gap laws' conductances (surrounding
// layer, Vargas-McCarthy, Bahrami) with an exact Jacobian, and its settings are checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/GasGapCases.h"
#include "thermal/modes/ParticleResistance.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;
using namespace tmdem::thermal::gas_test;

namespace {

// Three particles: 0-1 touching, 1-2 a near pair at 0.1 R, 0-2 beyond the cutoff; particle 0
// also near an isothermal wall at 400 K.
ThermalNetwork gas_network() {
  ThermalNetwork net;
  net.resize_nodes(3);
  net.heat_capacity_J_per_K = {1e-2, 2e-2, 1.5e-2};
  net.radius_m = {kR, kR, 0.8 * kR};
  net.add_edge(0, 1, 0.0, 0.0, 1e-5, true);
  net.add_edge(1, 2, 0.0, 0.1 * kR, 0.0, false);
  net.add_edge(0, 2, 0.0, 0.9 * kR, 0.0, false);
  net.add_wall_edge(0, 400.0, 0.0, -1, 0.05 * kR, 0.0, false);
  return net;
}

// Building the gas mode with `s` throws std::invalid_argument naming `key`.
void expect_gas_mode_refused(const ModeSettings& s, const std::string& key) {
  try {
    make_heat_transfer_mode("gas_conduction", s);
    ADD_FAILURE() << "built without error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

ModeSettings gas_settings(double model) {
  ModeSettings s;
  s.set("gas_conduction", "model", model);
  s.set("gas_conduction", "conductivity", 0.05);
  return s;
}

}  // namespace

TEST(GasConductionMode, FlowsAreTheLawsConductancesAndTheJacobianIsExact) {
  const auto net = gas_network();
  auto sys = make_system(net, {"gas_conduction"}, gas_settings(1.0));  // surrounding_layer
  const std::vector<double> T{300.0, 350.0, 330.0};
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  const double H01 = surrounding_layer_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05, kLayer, kL);
  const double H12 = surrounding_layer_conductance_W_per_K(spheres(kR, 0.8 * kR, 0.1 * kR), 0.05, kLayer, kL);
  const double Hw = surrounding_layer_conductance_W_per_K(plane(kR, 0.05 * kR), 0.05, kLayer, kL);
  EXPECT_GT(H12, 0.0);
  EXPECT_DOUBLE_EQ(q[0], H01 * (350.0 - 300.0) + Hw * (400.0 - 300.0));  // nothing from 2
  EXPECT_DOUBLE_EQ(q[2], H12 * (350.0 - 330.0));
  EXPECT_NEAR(q[0] + q[1] + q[2], Hw * 100.0, 1e-15);  // pairs conserve; only the wall adds
  EXPECT_DOUBLE_EQ(boundary, Hw * 100.0);
  // Jacobian against central differences (the flows are linear: exact to round-off).
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  std::vector<double> values(sys->pattern().nonzeros());
  sys->jacobian_values(J, values);
  for (int j = 0; j < 3; ++j) {
    auto Tp = T, Tm = T;
    Tp[j] += 1.0;
    Tm[j] -= 1.0;
    std::vector<double> qp(3), qm(3);
    ASSERT_TRUE(sys->time_derivative(Tp, qp, boundary));
    ASSERT_TRUE(sys->time_derivative(Tm, qm, boundary));
    const auto& P = sys->pattern();
    for (int i = 0; i < 3; ++i) {
      double Jij = 0.0;
      for (auto s = P.column_start[j]; s < P.column_start[j + 1]; ++s)
        if (P.row_index[s] == i) Jij = values[s];
      EXPECT_NEAR(Jij, 0.5 * (qp[i] - qm[i]), 1e-12) << i << "," << j;
    }
  }
}

TEST(GasConductionMode, VargasMcCarthyCountsTouchingPairsOnly) {
  auto sys = make_system(gas_network(), {"gas_conduction"}, gas_settings(0.0));
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(std::vector<double>{300.0, 350.0, 330.0}, q, boundary));
  const double H01 = vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05);
  EXPECT_DOUBLE_EQ(q[0], H01 * 50.0);
  EXPECT_EQ(q[2], 0.0);
  EXPECT_EQ(boundary, 0.0);
}

// fluid.model = "bahrami": the macro-gap of touching pairs (and touching isothermal walls) with
// the gas parameter M of the section's pressure, mean free path, accommodation, gamma and Pr;
// near pairs get nothing, and without a pressure the model is refused naming the key.
TEST(GasConductionMode, BahramiCountsTouchingPairsWithTheSectionsGasParameter) {
  ThermalNetwork net = gas_network();
  net.add_wall_edge(2, 400.0, 0.0, -1, 0.0, 2e-6, true);  // 2 rests on a wall at 400 K
  ModeSettings s = gas_settings(2.0);
  s.set("gas_conduction", "pressure", 101325.0);
  s.set("gas_conduction", "accommodation", 0.7);
  s.set("gas_conduction", "heat_capacity_ratio", 1.4);
  s.set("gas_conduction", "prandtl", 0.69);
  auto sys = make_system(net, {"gas_conduction"}, s);
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(std::vector<double>{300.0, 350.0, 330.0}, q, boundary));
  const double M = 2.0 * 1.3 / 0.7 * (2.8 / 2.4) * 6.8e-8 / 0.69;  // mean_free_path's default
  const double H01 = bahrami_macrogap_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05, M);
  const double Hw = bahrami_macrogap_conductance_W_per_K(plane(0.8 * kR, 0.0, 2e-6), 0.05, M);
  EXPECT_NEAR(q[0], H01 * 50.0, 1e-12 * H01 * 50.0);  // not the near wall at 0.05 R
  EXPECT_NEAR(q[2], Hw * 70.0, 1e-12 * Hw * 70.0);    // not the near pair 1-2
  EXPECT_NEAR(boundary, Hw * 70.0, 1e-12 * Hw * 70.0);
  s.set("gas_conduction", "pressure", 0.0);
  expect_gas_mode_refused(s, "gas_conduction.pressure");
}

TEST(GasConductionMode, AModelIndexOutsideTheChoicesIsRefused) {
  // The scene maps names to indices (an unknown name is refused there, listing the valid ones:
  // test_scene_gas); a bad index set directly is refused naming the key.
  ModeSettings s;
  s.set("gas_conduction", "model", 3.0);
  expect_gas_mode_refused(s, "gas_conduction.model");
}
