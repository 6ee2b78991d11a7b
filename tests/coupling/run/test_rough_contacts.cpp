// thermal.conductance = "bahrami" and fluid.model = "bahrami" through the network builder and the
// built system, for a particle pair and particles on an isothermal wall: each contact conducts
// by the rough-contact law with the pair's (or the wall's) surfaces, its micro-gap holding the
// [fluid]'s gas only while effects.gas_conduction is on; an unloaded contact conducts through
// the gas gap alone; the heat flows are those conductances.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "mechanics/model/PairIndex.h"
#include "support/SceneBuilder.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/modes/RoughContactConductance.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

constexpr double kRoughRadius_m = 1e-3;
constexpr double kRoughFloor_K = 350.0, kRoughStart_K = 300.0;
constexpr double kRoughForce_N = 0.05;

// Rough steel spheres (sigma 0.5 um, m 0.08, H_mic 3 GPa) side by side on a smoother, softer
// floor (sigma 0.1 um, m 0.05, H_mic 1.5 GPa, k 200 W/(m K)), in air or in vacuum.
Scene rough_spheres_on_a_floor(bool gas) {
  SceneBuilder s;
  s.set({{"simulation.duration", 1.0}, {"thermal.conductance", "bahrami"}, {"effects.gas_conduction", gas}})
      .add("material", steel({{"roughness", 0.5e-6}, {"asperity_slope", 0.08}, {"microhardness", 3e9}}));
  if (gas)
    s.set({{"fluid.model", "bahrami"},
           {"fluid.conductivity", 0.027},
           {"fluid.pressure", 101325.0},
           {"fluid.mean_free_path", 68e-9},
           {"fluid.accommodation", 0.7},
           {"fluid.heat_capacity_ratio", 1.4},
           {"fluid.prandtl", 0.69}});
  const std::string text =
      s.add("material", steel({{"name", "floor"},
                               {"conductivity", 200.0},
                               {"roughness", 0.1e-6},
                               {"asperity_slope", 0.05},
                               {"microhardness", 1.5e9}}))
          .add("particle", particle({0.0, kRoughRadius_m, 0.0}, {{"temperature", kRoughStart_K}}))
          .add("particle", particle({2.0 * kRoughRadius_m, kRoughRadius_m, 0.0}, {{"temperature", kRoughStart_K}}))
          .add("wall", floor_wall({{"temperature", kRoughFloor_K}, {"material", "floor"}}));
  return load_scene_text(text, "rough.toml");
}

// The bodies as the scene gives them (support/SceneBuilder.h's steel: k 50, E 210 GPa, nu 0.3).
thermal::ContactBody rough_sphere() {
  return {kRoughRadius_m, 50.0, 2.1e11, 0.3, 0.5e-6, 0.08, 3e9};
}
thermal::ContactBody floor_body() {
  return {std::numeric_limits<double>::infinity(), 200.0, 2.1e11, 0.3, 0.1e-6, 0.05, 1.5e9};
}
// Air as [fluid] gives it: M = 2 (2 - 0.7)/0.7 (2 x 1.4 / 2.4) 68 nm / 0.69.
thermal::ContactGas rough_air() {
  return {0.027, 2.0 * 1.3 / 0.7 * (2.8 / 2.4) * 68e-9 / 0.69};
}

mechanics::ParticleSet two_spheres() {
  mechanics::ParticleSet geometry;
  geometry.add({0.0, kRoughRadius_m, 0.0}, kRoughRadius_m, 1.0, 0);
  geometry.add({2.0 * kRoughRadius_m, kRoughRadius_m, 0.0}, kRoughRadius_m, 1.0, 0);
  return geometry;
}

// Sphere 0 pressed on its neighbour and on the floor, sphere 1 resting on the floor unloaded.
ContactList rough_contacts() {
  ContactList contacts;
  contacts.add(0, 1, kRoughForce_N);
  contacts.add(0, mechanics::wall_code<std::int64_t>(0), kRoughForce_N);
  contacts.add(1, mechanics::wall_code<std::int64_t>(0), 0.0);
  return contacts;
}

TEST(RoughContacts, PairsAndWallsConductByTheRoughLawWithTheGasOnlyWhenItIsOn) {
  for (const bool gas : {false, true}) {
    SCOPED_TRACE(gas);
    const Scene scene = rough_spheres_on_a_floor(gas);
    const ThermalNetworkBuilder builder(scene);
    ContactList contacts = rough_contacts();
    thermal::ThermalNetwork net = builder.nodes();
    const auto geometry = two_spheres();
    builder.build_edges(contacts, net, nullptr, gas ? &geometry : nullptr);
    const thermal::ContactGas medium = gas ? rough_air() : thermal::ContactGas{};
    const double pair = thermal::rough_contact_conductance_W_per_K(rough_sphere(), rough_sphere(),
                                                                   kRoughForce_N, medium);
    const double wall = thermal::rough_contact_conductance_W_per_K(rough_sphere(), floor_body(),
                                                                   kRoughForce_N, medium);
    EXPECT_NEAR(contacts.conductance_W_per_K[0], pair, 1e-14 * pair);
    EXPECT_NEAR(contacts.conductance_W_per_K[1], wall, 1e-14 * wall);
    EXPECT_EQ(contacts.conductance_W_per_K[2], 0.0);  // unloaded: no spot
    // Rough surfaces conduct less than the Hertz spot of the same force.
    const double hertz = thermal::hertz_conductance_W_per_K(rough_sphere(), rough_sphere(), kRoughForce_N);
    EXPECT_LT(pair, hertz);
    if (gas) {  // the micro-gap adds to the vacuum value
      EXPECT_GT(pair, thermal::rough_contact_conductance_W_per_K(rough_sphere(), rough_sphere(),
                                                                 kRoughForce_N, {}));
    }
  }
  // With the gas switched off no gas mode is built at all.
  const int before = thermal::heat_transfer_mode_constructions("gas_conduction");
  const Scene vacuum = rough_spheres_on_a_floor(false);
  ContactList contacts = rough_contacts();
  build_thermal_system(vacuum, contacts);
  EXPECT_EQ(thermal::heat_transfer_mode_constructions("gas_conduction"), before);
}

// The built system's flows: into sphere 0 its contact with the floor plus the macro-gap of that
// contact (Hertz disc) and of its pair; into the unloaded sphere 1 the floor's gas alone (a = 0).
TEST(RoughContacts, AnUnloadedContactConductsThroughTheGasGapAlone) {
  const Scene scene = rough_spheres_on_a_floor(true);
  ContactList contacts = rough_contacts();
  const auto geometry = two_spheres();
  const auto system = build_thermal_system(scene, contacts, &geometry);
  std::vector<double> T{kRoughStart_K, kRoughStart_K}, q(2);
  double boundary = 0.0;
  ASSERT_TRUE(system->heat_flow(T, q, boundary));
  const double M = rough_air().gas_parameter_m, dT = kRoughFloor_K - kRoughStart_K;
  const double a_wall = thermal::hertz_contact_radius_m(rough_sphere(), floor_body(), kRoughForce_N);
  const double gas_loaded = thermal::bahrami_macrogap_conductance_W_per_K(
      {kRoughRadius_m, std::numeric_limits<double>::infinity(), 0.0, a_wall}, 0.027, M);
  const double gas_unloaded = thermal::bahrami_macrogap_conductance_W_per_K(
      {kRoughRadius_m, std::numeric_limits<double>::infinity(), 0.0, 0.0}, 0.027, M);
  // The closed form of the sphere on a plane: 2 pi k_f [(u + M) ln((u + M) / M) - u], u = R.
  EXPECT_NEAR(gas_unloaded,
              2.0 * std::numbers::pi * 0.027 *
                  ((kRoughRadius_m + M) * std::log((kRoughRadius_m + M) / M) - kRoughRadius_m),
              1e-10 * gas_unloaded);
  const double contact = thermal::rough_contact_conductance_W_per_K(rough_sphere(), floor_body(),
                                                                    kRoughForce_N, rough_air());
  EXPECT_NEAR(q[1], gas_unloaded * dT, 1e-12 * q[1]);
  EXPECT_NEAR(q[0], (contact + gas_loaded) * dT, 1e-12 * q[0]);  // equal temperatures: no pair flow
  EXPECT_NEAR(boundary, q[0] + q[1], 1e-12 * boundary);
}

}  // namespace
}  // namespace tmdem::coupling
