// effects.friction_heat: the mechanical energy the contacts dissipate becomes heat, half in each
// body, against closed-form slip work and inelastic-impact losses, with the run summary's
// mechanical energy line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

#include "coupling/run/CoupledRun.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "support/RunSceneText.h"
#include "support/SceneBuilder.h"
#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

constexpr double kG = 9.81, kRadius = 1e-3, kDensity = 7800.0, kSpecificHeat = 460.0, kMu = 0.3;
// Starting at 1 K keeps the round-off of T itself (ulp(1 K) = 2.2e-16 K per step) far below 1e-9
// of the rises checked here (~1e-4 K); nothing here depends on the temperature level.
constexpr double kT0 = 1.0;
const double kMass = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius * kDensity;

RunOutcome run(const std::string& text, const std::string& name) {
  auto outcome = run_scene_text(text, name);
  EXPECT_EQ(outcome.exit_code, 0) << outcome.summary.message;
  return outcome;
}

// Steel with mu = 0.3, dynamic mechanics, friction heat on, everything else adiabatic;
// thermal.coupling = "restart" (see SlippingSphereOnInclineHeatsByHalfTheSlipWork).
SceneBuilder friction_scene(double duration, std::initializer_list<double> gravity) {
  return SceneBuilder()
      .set("simulation.duration", duration)
      .set("simulation.gravity", gravity)
      .set("effects.mechanics", "dynamic")
      .set("effects.friction_heat", true)
      .set("mechanics.tolerance", 1e-12)
      .set(tolerances(1e-10))
      .set("thermal.coupling", "restart")
      .set(output("out.h5", duration))
      .add("material", steel({{"friction", kMu}}));
}

// One steel sphere at rest on the floor y = 0 under gravity tilted by alpha (an incline).
SceneBuilder incline_scene(double alpha, double duration) {
  return friction_scene(duration, {kG * std::sin(alpha), -kG * std::cos(alpha), 0.0})
      .add("particle", particle({0.0, kRadius, 0.0}, {{"temperature", kT0}}))
      .add("wall", floor_wall());
}

// A sphere on a 50 degree incline (tan a > 7/2 mu: it slips while it spins up) dissipates the
// slip work mu m g cos(a) * 1/2 g (sin a - 7/2 mu cos a) t^2; half of it heats the sphere, the
// floor's half is lost to the floor.
TEST(FrictionHeat, SlippingSphereOnInclineHeatsByHalfTheSlipWork) {
  const double alpha = 50.0 * std::numbers::pi / 180.0, t = 0.3;
  // The power is constant over each mechanical step and jumps between steps: CVODE and IDA
  // integrate it exactly only from a fresh start after each jump ("restart" every step;
  // "continue" whenever the source changed, see ContinuedCouplingReceivesAllTheHeat).
  for (const char* integrator : {"cvode", "ida", "explicit"}) {
    const auto outcome =
        run(incline_scene(alpha, t).set("thermal.integrator", integrator).str(), "slip");
    const double slip_work = kMu * kMass * kG * std::cos(alpha) * 0.5 * kG *
                             (std::sin(alpha) - 3.5 * kMu * std::cos(alpha)) * t * t;
    const auto& e = outcome.summary.energy;
    ASSERT_TRUE(e.mechanical.has_value());
    const auto& m = *e.mechanical;
    EXPECT_NEAR(m.contact_dissipation_J, slip_work, 1e-9 * slip_work) << integrator;
    EXPECT_TRUE(m.heat);
    EXPECT_LT(m.heat_error_rel, 1e-9) << integrator;
    EXPECT_LT(m.balance_error_rel, 1e-12) << integrator;
    EXPECT_EQ(m.numerical_dissipation_J, 0.0);  // theta = 1/2
    EXPECT_NEAR(e.final_J - e.initial_J, 0.5 * slip_work, 1e-9 * slip_work) << integrator;
    EXPECT_NEAR(e.boundary_heat_J, 0.5 * slip_work, 1e-9 * slip_work) << integrator;
    EXPECT_NEAR(outcome.final_temperature_K[0] - kT0, 0.5 * slip_work / (kMass * kSpecificHeat),
                1e-9 * slip_work / (kMass * kSpecificHeat));
  }
}

// thermal.coupling = "continue" keeps the BDF history while the contacts only change force, but
// the friction heat is a source that jumps at every mechanical step: a history carried across
// the jumps integrated it only to the error test's tolerance, relative to T (at 300 K the
// sphere received 0.32% too little). The run now starts the integrator afresh whenever the
// step's dissipated powers changed, so the heat received equals the heat generated.
TEST(FrictionHeat, ContinuedCouplingReceivesAllTheHeat) {
  const double alpha = 50.0 * std::numbers::pi / 180.0, t = 0.3, T0 = 300.0;
  const double slip_work = kMu * kMass * kG * std::cos(alpha) * 0.5 * kG *
                           (std::sin(alpha) - 3.5 * kMu * std::cos(alpha)) * t * t;
  for (const char* integrator : {"cvode", "ida", "explicit"}) {
    SCOPED_TRACE(integrator);
    const auto text = friction_scene(t, {kG * std::sin(alpha), -kG * std::cos(alpha), 0.0})
                          .set("thermal.coupling", "continue")
                          .set("thermal.integrator", integrator)
                          .add("particle", particle({0.0, kRadius, 0.0}, {{"temperature", T0}}))
                          .add("wall", floor_wall())
                          .str();
    const auto outcome = run(text, "continue");
    const auto& e = outcome.summary.energy;
    const auto& m = *e.mechanical;
    EXPECT_NEAR(m.contact_dissipation_J, slip_work, 1e-9 * slip_work);
    // The heat the thermal side integrated (its boundary-heat quadrature) is half the slip work.
    EXPECT_NEAR(e.boundary_heat_J, 0.5 * slip_work, 1e-9 * slip_work);
    // The summary's own check: the integrator's quadrature of the sphere's share.
    EXPECT_NEAR(m.heat_received_J, 0.5 * slip_work, 1e-9 * slip_work);
    EXPECT_LT(m.heat_error_rel, 1e-9);
  }
}

// At 20 degrees it rolls without slipping: no heat (to round-off of the potential energy lost).
TEST(FrictionHeat, RollingSphereStaysCold) {
  const double alpha = 20.0 * std::numbers::pi / 180.0;
  const auto outcome = run(incline_scene(alpha, 0.3).str(), "roll");
  const auto& m = *outcome.summary.energy.mechanical;
  // It went down: potential energy m g . dx became kinetic, and none was lost.
  const double speed = 5.0 / 7.0 * kG * std::sin(alpha) * 0.3;
  const double kinetic = 0.5 * kMass * speed * speed * 7.0 / 5.0;  // translation + spin
  EXPECT_LT(std::abs(m.energy_change_J), 1e-12 * kinetic);
  EXPECT_LT(std::abs(m.contact_dissipation_J), 1e-12 * kinetic);
  EXPECT_LT(std::abs(outcome.final_temperature_K[0] - kT0), 1e-14);
}

// A sphere dropped onto a fixed sphere (no walls): the contact between two particles heats both
// by half of what it dissipated, which is all the mechanical energy the falling sphere lost.
TEST(FrictionHeat, ImpactBetweenParticlesHeatsBothEqually) {
  const double height = 5e-3;
  const auto text = friction_scene(0.1, {0.0, -kG, 0.0})
                        .add("particle", particle({0.0, 0.0, 0.0}, {{"temperature", kT0}}))
                        .add("particle", particle({0.0, 2.0 * kRadius + height, 0.0},
                                                  {{"temperature", kT0}}))
                        .add("assign", assign_ids({0}, {{"fixed", true}}))
                        .str();
  const auto outcome = run(text, "pair");
  const auto& m = *outcome.summary.energy.mechanical;
  const double arrival = kMass * kG * height;
  EXPECT_NEAR(m.contact_dissipation_J, -m.energy_change_J, 1e-12 * arrival);
  EXPECT_NEAR(m.contact_dissipation_J, arrival, 0.01 * arrival);
  EXPECT_LT(m.heat_error_rel, 1e-9);
  const double rise = 0.5 * m.contact_dissipation_J / (kMass * kSpecificHeat);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(outcome.final_temperature_K[std::size_t(i)] - kT0, rise, 1e-9 * rise)
        << "sphere " << i;
}

// A sphere dropped onto the floor: the impact dissipates its kinetic energy (plus the little
// fall during the impact step), exactly the mechanical energy it lost.
TEST(FrictionHeat, ImpactOnTheFloorTurnsTheEnergyLostIntoHeat) {
  const double height = 5e-3;
  const auto text = friction_scene(0.1, {0.0, -kG, 0.0})
                        .add("particle", particle({0.0, kRadius + height, 0.0}, {{"temperature", kT0}}))
                        .add("wall", floor_wall())
                        .str();
  const auto outcome = run(text, "impact");
  const auto& s = outcome.summary;
  const auto& m = *s.energy.mechanical;
  const double arrival = kMass * kG * height;  // kinetic energy on arrival, continuous fall
  EXPECT_NEAR(m.contact_dissipation_J, -m.energy_change_J, 1e-12 * arrival);
  EXPECT_NEAR(m.contact_dissipation_J, arrival, 0.01 * arrival);
  EXPECT_LT(m.heat_error_rel, 1e-9);
  EXPECT_NEAR(s.energy.final_J - s.energy.initial_J, 0.5 * m.contact_dissipation_J,
              1e-9 * arrival);
}

// Off by default: a dynamic run without the switch never builds the mode and writes no heat
// keys; the mechanical account is there all the same.
TEST(FrictionHeat, OffIsNeverBuilt) {
  const int before = thermal::heat_transfer_mode_constructions("friction_heat");
  const auto outcome =
      run(incline_scene(0.9, 0.05).erase("effects.friction_heat").str(), "off");
  EXPECT_EQ(thermal::heat_transfer_mode_constructions("friction_heat"), before);
  const auto& m = *outcome.summary.energy.mechanical;
  EXPECT_FALSE(m.heat);
  EXPECT_GT(m.contact_dissipation_J, 0.0);
  EXPECT_EQ(outcome.final_temperature_K[0], kT0);
  const auto json = outcome.summary.to_json();
  EXPECT_FALSE(json["energy"]["mechanical"].contains("heat_generated_J"));
}

// Without a moving packing there is nothing to dissipate: the switch is refused, naming the key.
TEST(FrictionHeat, NeedsDynamicMechanics) {
  for (const char* mechanics : {"settle", "off"}) {
    const auto text = incline_scene(0.5, 1.0)
                          .set("effects.mechanics", mechanics)
                          .set("thermal.conductance", "constant")
                          .str();
    try {
      load_scene_text(text, "scene.toml");
      ADD_FAILURE() << mechanics << " accepted";
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("effects.friction_heat"), std::string::npos) << message;
      EXPECT_NE(message.find("\"dynamic\""), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace tmdem::coupling
