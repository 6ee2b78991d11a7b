// Integrators against exact solutions: two nodes, a chain, observed convergence order.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "thermal/ThermalTestSupport.h"
#include "thermal/integrators/ExplicitIntegrator.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// Two nodes, C1 != C2: the difference decays as exp(-H (1/C1 + 1/C2) t) around the
// capacity-weighted mean.
std::vector<double> two_node_exact(double C1, double C2, double H, double T1, double T2, double t) {
  const double mean = (C1 * T1 + C2 * T2) / (C1 + C2);
  const double d = (T1 - T2) * std::exp(-H * (1.0 / C1 + 1.0 / C2) * t);
  return {mean + d * C2 / (C1 + C2), mean - d * C1 / (C1 + C2)};
}

ThermalNetwork two_nodes(double C1, double C2, double H) {
  ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {C1, C2};
  net.add_edge(0, 1, H);
  return net;
}

double two_node_error(const std::string& integrator, IntegratorSettings s) {
  const double C1 = 2e-3, C2 = 5e-3, H = 1e-4, t = 30.0;
  auto sys = make_system(two_nodes(C1, C2, H), {"contact_conduction"});
  const auto r = run(*sys, integrator, s, {373.15, 293.15}, t);
  const auto ex = two_node_exact(C1, C2, H, 373.15, 293.15, t);
  return std::max(std::abs(r.T[0] - ex[0]), std::abs(r.T[1] - ex[1]));
}

}  // namespace

TEST(TwoNodes, MatrixExponentialAgreesWithClosedForm) {
  // The dense reference used everywhere else, checked once against the closed form.
  const auto net = two_nodes(2e-3, 5e-3, 1e-4);
  const auto ex = exact_temperatures(affine_system(net, {}, false), {373.15, 293.15}, 30.0);
  const auto cf = two_node_exact(2e-3, 5e-3, 1e-4, 373.15, 293.15, 30.0);
  EXPECT_NEAR(ex(0), cf[0], 1e-11);
  EXPECT_NEAR(ex(1), cf[1], 1e-11);
}

TEST(TwoNodes, CvodeErrorFallsWithTolerance) {
  double previous = 1e300;
  for (double rtol : {1e-3, 1e-5, 1e-7, 1e-9}) {
    IntegratorSettings s;
    s.relative_tolerance = rtol;
    s.absolute_tolerance_K = rtol;
    const double err = two_node_error("cvode", s);
    EXPECT_LT(err, previous) << "rtol " << rtol;
    EXPECT_LT(err, 2000.0 * rtol * 373.15) << "rtol " << rtol;
    previous = err;
  }
  EXPECT_LT(previous, 1e-5);
}

TEST(TwoNodes, IdaErrorFallsWithTolerance) {
  double previous = 1e300;
  for (double rtol : {1e-3, 1e-5, 1e-7, 1e-9}) {
    IntegratorSettings s;
    s.relative_tolerance = rtol;
    s.absolute_tolerance_K = rtol;
    const double err = two_node_error("ida", s);
    EXPECT_LT(err, previous) << "rtol " << rtol;
    previous = err;
  }
  EXPECT_LT(previous, 1e-5);
}

TEST(TwoNodes, ExplicitIsFirstOrder) {
  // Halving the step halves the error, within 10%.
  IntegratorSettings s;
  s.explicit_step_s = 0.4;
  double previous = two_node_error("explicit", s);
  for (int k = 0; k < 4; ++k) {
    s.explicit_step_s /= 2.0;
    const double err = two_node_error("explicit", s);
    const double ratio = previous / err;
    EXPECT_NEAR(ratio, 2.0, 0.2) << "step " << s.explicit_step_s;
    previous = err;
  }
}

class ChainTest : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(ChainTest, MatchesExactModalSolution) {
  // N equal nodes, insulated ends: T_i(t) = sum_k c_k cos(k pi (i + 1/2) / N) exp(-lambda_k t),
  // lambda_k = (2 H / C) (1 - cos(k pi / N)).
  const auto [integrator, solver] = GetParam();
  const int N = 40;
  const double C = 3.6e-3, H = 2e-4, t = 20.0;
  auto sys = make_system(chain_network(N, C, H), {"contact_conduction"});
  std::vector<double> T0(N, 293.15);
  T0[0] = 373.15;
  T0[7] = 330.0;
  IntegratorSettings s;
  s.linear_solver = solver_kind(solver);
  s.relative_tolerance = 1e-9;
  s.absolute_tolerance_K = 1e-9;
  s.explicit_step_s = 1e-3;
  const auto r = run(*sys, integrator, s, T0, t);
  double max_err = 0.0;
  for (int i = 0; i < N; ++i) {
    double Ti = 0.0;
    for (int k = 0; k < N; ++k) {
      double ck = 0.0;  // projection of T0 on mode k (orthogonal cosine basis)
      for (int j = 0; j < N; ++j) ck += T0[j] * std::cos(k * std::numbers::pi * (j + 0.5) / N);
      ck *= (k == 0 ? 1.0 : 2.0) / N;
      const double lambda = 2.0 * H / C * (1.0 - std::cos(k * std::numbers::pi / N));
      Ti += ck * std::cos(k * std::numbers::pi * (i + 0.5) / N) * std::exp(-lambda * t);
    }
    max_err = std::max(max_err, std::abs(r.T[i] - Ti));
  }
  // The explicit error is set by its step (first order), the others' by the tolerance.
  EXPECT_LT(max_err, integrator == "explicit" ? 2e-3 : 1e-5) << integrator << "/" << solver;
}

INSTANTIATE_TEST_SUITE_P(Integrators, ChainTest,
                         ::testing::Values(std::make_tuple("cvode", "klu"),
                                           std::make_tuple("cvode", "pcg"),
                                           std::make_tuple("cvode", "amg"),
                                           std::make_tuple("ida", "klu"),
                                           std::make_tuple("ida", "pcg"),
                                           std::make_tuple("ida", "amg"),
                                           std::make_tuple("explicit", "klu")));

TEST(Explicit, StepAboveBoundIsRefusedWithTheBound) {
  auto sys = make_system(chain_network(10, 1e-3, 1e-4), {"contact_conduction"});
  // Gershgorin: lambda <= 2 * 2H/C for interior nodes, so the bound is C / (2 H) = 5 s.
  const double bound = sys->explicit_stability_bound_s(400.0);
  EXPECT_NEAR(bound, 5.0, 1e-12);
  IntegratorSettings s;
  s.explicit_step_s = 1.01 * bound;
  auto integ = make_thermal_integrator("explicit", *sys, s);
  try {
    integ->initialize(0.0, std::vector<double>(10, 300.0), 0.0);
    FAIL() << "a step 1% above the bound was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("5 s"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("explicit_step"), std::string::npos) << e.what();
  }
}

TEST(Explicit, AtNineTenthsOfBoundStaysBounded) {
  const int N = 30;
  auto sys = make_system(chain_network(N, 1e-3, 1e-4), {"contact_conduction"});
  std::vector<double> T0(N);
  for (int i = 0; i < N; ++i) T0[i] = (i % 2) ? 400.0 : 300.0;  // the stiffest mode, excited
  IntegratorSettings s;  // explicit_step = 0: 0.9 of the bound
  auto integ = make_thermal_integrator("explicit", *sys, s);
  integ->initialize(0.0, T0, 0.0);
  auto* ex = dynamic_cast<ExplicitIntegrator*>(integ.get());
  ASSERT_NE(ex, nullptr);
  EXPECT_NEAR(ex->step_s(), 0.9 * ex->stability_bound_s(), 1e-15);
  for (int k = 1; k <= 100; ++k) {
    integ->advance_to(k * 10.0);
    for (double T : integ->temperatures_K()) {
      ASSERT_GE(T, 300.0 - 1e-9);
      ASSERT_LE(T, 400.0 + 1e-9);
    }
  }
}

TEST(Registry, UnknownNamesListValidOnes) {
  auto sys = make_system(chain_network(3, 1e-3, 1e-4), {"contact_conduction"});
  try {
    make_thermal_integrator("rk4", *sys, {});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cvode, ida, explicit"), std::string::npos) << e.what();
  }
  try {
    make_heat_transfer_mode("conduction_magic", {});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("valid types are: contact_conduction"), std::string::npos);
  }
}
