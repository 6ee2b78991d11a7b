// The Jacobian of the modes lives in a JacobianEvaluation the caller owns: computing the explicit
// stability bound (which evaluates J at T_max) between an integrator's Jacobian evaluation and
// its use must leave that Jacobian as it was. Before, the system kept one hidden cache and the
// bound overwrote it with J(T_max).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "thermal/ThermalTestSupport.h"
#include "thermal/system/JacobianEvaluation.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

constexpr double kSigma_W_per_m2K4 = 5.670374419e-8;

// Three particles in a chain, radiating: the diagonal of J depends on T (-4 eps sigma A T^3),
// so J at the bound's T_max differs from J at the run's temperatures.
ThermalNetwork radiating_chain() {
  ThermalNetwork net = chain_network(3, 2.0, 0.5);  // C = 2 J/K, H = 0.5 W/K
  for (std::size_t i = 0; i < 3; ++i) {
    net.surface_area_m2[i] = 1e-2;
    net.emissivity[i] = 0.8;
  }
  return net;
}

}  // namespace

TEST(JacobianEvaluation, StabilityBoundLeavesTheCallersJacobianUnchanged) {
  auto sys = make_system(radiating_chain(), {"contact_conduction", "radiation"});
  const std::vector<double> T{300.0, 400.0, 500.0};
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  std::vector<double> before(sys->pattern().nonzeros());
  sys->jacobian_values(J, before);
  const std::vector<double> v{1.0, -2.0, 0.5};
  std::vector<double> Jv_before(3);
  sys->jacobian_times(J, v, Jv_before);

  const double bound_s = sys->explicit_stability_bound_s(2000.0);
  ASSERT_TRUE(std::isfinite(bound_s));

  std::vector<double> after(before.size());
  sys->jacobian_values(J, after);
  std::vector<double> Jv_after(3);
  sys->jacobian_times(J, v, Jv_after);
  EXPECT_EQ(after, before);
  EXPECT_EQ(Jv_after, Jv_before);

  // And J is still the one at T, against the closed form: node 1 (middle, two edges)
  // dq/dT = -2 H - 4 eps sigma A T^3, divided by C.
  const double expected_middle =
      (-2 * 0.5 - 4 * 0.8 * kSigma_W_per_m2K4 * 1e-2 * std::pow(400.0, 3)) / 2.0;
  EXPECT_NEAR(after[std::size_t(sys->pattern().diagonal_slot[1])], expected_middle,
              1e-15 * std::abs(expected_middle));
  // The bound's own Jacobian (at 2000 K everywhere) is genuinely different, so the check has
  // teeth: the old shared cache would have held these values after the call.
  JacobianEvaluation at_bound;
  sys->evaluate_jacobian(std::vector<double>(3, 2000.0), at_bound);
  std::vector<double> bound_values(before.size());
  sys->jacobian_values(at_bound, bound_values);
  EXPECT_NE(bound_values, before);
}

TEST(JacobianEvaluation, BoundMatchesGershgorinOfTheChainAtTmax) {
  auto sys = make_system(radiating_chain(), {"contact_conduction", "radiation"});
  // Largest row sum is the middle node: 2 H (diagonal) + 2 H (edges) + 4 eps sigma A T^3.
  const double T_max = 2000.0;
  const double row_W_per_K = 4 * 0.5 + 4 * 0.8 * kSigma_W_per_m2K4 * 1e-2 * std::pow(T_max, 3);
  EXPECT_NEAR(sys->explicit_stability_bound_s(T_max), 2.0 / (row_W_per_K / 2.0),
              1e-14 * 2.0 / (row_W_per_K / 2.0));
}

TEST(JacobianEvaluation, EvaluationOfAnOlderContactGraphIsRefused) {
  auto sys = make_system(chain_network(3, 2.0, 0.5), {"contact_conduction"});
  JacobianEvaluation J;
  sys->evaluate_jacobian(std::vector<double>(3, 300.0), J);
  ThermalNetwork more = chain_network(3, 2.0, 0.5);
  more.add_edge(0, 2, 0.25);  // a new contact: the graph changes shape
  sys->replace_edges(more);
  std::vector<double> values(sys->pattern().nonzeros());
  EXPECT_THROW(sys->jacobian_values(J, values), std::logic_error);
  sys->evaluate_jacobian(std::vector<double>(3, 300.0), J);
  EXPECT_NO_THROW(sys->jacobian_values(J, values));
}
