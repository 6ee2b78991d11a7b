// The accuracy study's exact reference (coupling/ExactThermalReference.h) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/studies/ExactThermalReference.h"
#include "tests/coupling/studies/AffineTestNetworks.h"

namespace tmdem::coupling {
namespace {

using testing::convection_settings;
using testing::kAffineModes;
using testing::two_node_network;

// Two nodes: the mean sum C_i T_i / sum C_i stays, the difference decays at H (1/C1 + 1/C2).
TEST(ExactThermalReference, TwoNodesMatchClosedForm) {
  const double C1 = 0.015, C2 = 0.004, H = 1e-3, T10 = 373.15, T20 = 293.15;
  const auto sys = affine_thermal_system(two_node_network(C1, C2, H), {"contact_conduction"}, {});
  ASSERT_TRUE(sys);
  const double Tm = (C1 * T10 + C2 * T20) / (C1 + C2);
  const double rate = H * (1.0 / C1 + 1.0 / C2);
  for (double t : {0.0, 0.5, 3.0, 20.0, 200.0}) {
    const auto T = exact_affine_temperatures(*sys, std::vector<double>{T10, T20}, t);
    const double d = (T10 - T20) * std::exp(-rate * t);
    EXPECT_NEAR(T[0], Tm + C2 / (C1 + C2) * d, 1e-12 * Tm) << "t = " << t;
    EXPECT_NEAR(T[1], Tm - C1 / (C1 + C2) * d, 1e-12 * Tm) << "t = " << t;
  }
}

// One node with a held neighbour: T1 relaxes to the held temperature, which does not move.
TEST(ExactThermalReference, HeldNodeKeepsItsTemperature) {
  auto net = two_node_network(0.01, 0.02, 2e-3);
  net.held[1] = 1;
  const auto sys = affine_thermal_system(net, {"contact_conduction"}, {});
  ASSERT_TRUE(sys);
  const auto T = exact_affine_temperatures(*sys, std::vector<double>{300.0, 400.0}, 7.0);
  EXPECT_EQ(T[1], 400.0);
  EXPECT_NEAR(T[0], 400.0 - 100.0 * std::exp(-2e-3 / 0.01 * 7.0), 1e-12 * 400.0);
}

// Wall, convection and a source on one node: dT/dt = (Hw (Tw - T) + hA (Tf - T) + P) / C.
TEST(ExactThermalReference, AffineModesMatchClosedForm) {
  thermal::ThermalNetwork net;
  net.resize_nodes(1);
  net.heat_capacity_J_per_K[0] = 0.02;
  net.surface_area_m2[0] = 1.2e-5;
  net.heat_source_W[0] = 0.05;
  net.add_wall_edge(0, 350.0, 4e-4);
  const auto s = convection_settings(20.0, 280.0);
  const auto sys = affine_thermal_system(net, kAffineModes, s);
  ASSERT_TRUE(sys);
  const double hA = 20.0 * 1.2e-5, k = (4e-4 + hA) / 0.02;
  const double Tinf = (4e-4 * 350.0 + hA * 280.0 + 0.05) / (4e-4 + hA);
  for (double t : {1.0, 10.0, 100.0}) {
    const auto T = exact_affine_temperatures(*sys, std::vector<double>{300.0}, t);
    EXPECT_NEAR(T[0], Tinf + (300.0 - Tinf) * std::exp(-k * t), 1e-12 * Tinf) << "t = " << t;
  }
  // A mode that is off contributes nothing even if the network holds its data.
  const auto only_source = affine_thermal_system(net, {"heat_source"}, s);
  ASSERT_TRUE(only_source);
  const auto T = exact_affine_temperatures(*only_source, std::vector<double>{300.0}, 2.0);
  EXPECT_NEAR(T[0], 300.0 + 0.05 / 0.02 * 2.0, 1e-12 * 300.0);
}

// The modes state their own affine parts: a mode that has none is named in the reason, and an
// unknown name is refused by the mode registry with the valid names.
TEST(ExactThermalReference, RadiationHasNoExactReference) {
  std::string why;
  EXPECT_FALSE(affine_thermal_system(two_node_network(1.0, 1.0, 1.0), {"contact_conduction", "radiation"},
                                     {}, &why));
  EXPECT_NE(why.find("radiation"), std::string::npos) << why;
  EXPECT_EQ(why.find("contact_conduction"), std::string::npos) << why;
  try {
    (void)affine_thermal_system(two_node_network(1.0, 1.0, 1.0), {"something_new"}, {});
    FAIL() << "an unknown mode name was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("contact_conduction"), std::string::npos) << e.what();
  }
}

// Properties that follow T make the network nonlinear, whatever its modes.
TEST(ExactThermalReference, TemperatureDependentNetworkHasNoExactReference) {
  auto net = two_node_network(1.0, 1.0, 1.0);
  thermal::ModeSettings s;
  const auto linear = affine_thermal_system(net, {"contact_conduction"}, s);
  ASSERT_TRUE(linear);
  net.wall_temperature_tables.resize(1);
  std::string why;
  EXPECT_FALSE(affine_thermal_system(net, {"contact_conduction"}, s, &why));
  EXPECT_NE(why.find("table"), std::string::npos) << why;
}

// A stiff pair (capacities 1e6 apart) over a long time, |A| t up to 1e5: scaling and squaring
// loses about |A t| eps relative (observed 2e-12, 5e-10 K), far below the study's 1e-6 K target.
TEST(ExactThermalReference, StiffPairOverLongTime) {
  const double C1 = 1e-5, C2 = 10.0, H = 1e-3, T10 = 400.0, T20 = 300.0;
  const auto sys = affine_thermal_system(two_node_network(C1, C2, H), {"contact_conduction"}, {});
  const double Tm = (C1 * T10 + C2 * T20) / (C1 + C2);
  const double rate = H * (1.0 / C1 + 1.0 / C2);
  for (double t : {1e-3, 0.05, 1e3}) {
    const auto T = exact_affine_temperatures(*sys, std::vector<double>{T10, T20}, t);
    const double d = (T10 - T20) * std::exp(-rate * t);
    EXPECT_NEAR(T[0], Tm + C2 / (C1 + C2) * d, 2e-9) << "t = " << t;
    EXPECT_NEAR(T[1], Tm - C1 / (C1 + C2) * d, 2e-9) << "t = " << t;
  }
}

}  // namespace
}  // namespace tmdem::coupling
