// ThermalIntegrator::dissipation_heat_J: the integrators integrate the friction-heat power on its
// own, so a run can check what the thermal side received against the exact integral of the
// piecewise-constant source. A source that jumps between advances is received exactly when the
// integrator restarts at each jump, and the measure shows the loss when a BDF history is carried
// across the jumps instead (what thermal.coupling = "continue" did before it restarted there).
#include <gtest/gtest.h>

#include <cmath>

#include "thermal/ThermalTestSupport.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// Two particles with a contact that dissipates P_k in step k (half into each), one on the
// floor (its wall half leaves): the particles get 3/2 P_k per step.
struct Received {
  double received_J = 0.0, exact_J = 0.0, energy_J = 0.0;
};

Received slide(const std::string& integrator, bool restart_at_jumps) {
  ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {1.5e-2, 1.5e-2};
  auto sys = make_system(net, {"friction_heat"});
  auto integ = make_thermal_integrator(integrator, *sys, tight_settings("klu", 1e-10));
  const std::vector<double> T0{300.0, 300.0};
  integ->initialize(0.0, T0, 0.0);
  Received r;
  const double h = 1e-3;
  for (int k = 1; k <= 300; ++k) {
    const double P = 1e-4 * k;  // grows like the slip power of an accelerating sphere
    ThermalNetwork edges = net;
    edges.clear_edges();
    edges.add_dissipation(0, 1, P);
    edges.add_dissipation(0, -1, P);
    sys->replace_edges(edges);
    if (restart_at_jumps) integ->restart();
    integ->advance_to(k * h);
    r.exact_J += 1.5 * P * h;
  }
  r.received_J = integ->dissipation_heat_J();
  r.energy_J = sys->thermal_energy_J(integ->temperatures_K()) - sys->thermal_energy_J(T0);
  return r;
}

}  // namespace

TEST(DissipationHeat, RestartAtEachJumpReceivesTheExactIntegral) {
  for (const std::string integrator : {"cvode", "ida", "explicit"}) {
    const auto r = slide(integrator, true);
    EXPECT_NEAR(r.received_J, r.exact_J, 1e-13 * r.exact_J) << integrator;
    // What the temperatures took up is what was received (round-off of C T at 300 K).
    EXPECT_NEAR(r.energy_J, r.received_J, 1e-9 * r.exact_J) << integrator;
  }
}

TEST(DissipationHeat, HistoryCarriedAcrossTheJumpsShowsInTheMeasure) {
  for (const std::string integrator : {"cvode", "ida"}) {
    const auto r = slide(integrator, false);
    // The measure is the temperatures' own account, and it is off the exact integral.
    EXPECT_NEAR(r.energy_J, r.received_J, 1e-9 * r.exact_J) << integrator;
    EXPECT_GT(std::abs(r.received_J - r.exact_J), 1e-6 * r.exact_J) << integrator;
  }
}
