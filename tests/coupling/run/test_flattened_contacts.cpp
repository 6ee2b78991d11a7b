// thermal.contact_flattening through the network builder: a loaded contact conducts through a
// spot of radius max(a_Hertz, f R*), and the gas of the pair sees the same solid disc (the
// network's contact radius), for a particle pair and a particle on an isothermal wall.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/scene/SceneLoader.h"
#include "mechanics/model/PairIndex.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

constexpr double kFlatRadius_m = 1e-3;          // m
constexpr double kFlatSteelK = 50.0;     // W/(m K)
constexpr double kFlatSteelE = 2.1e11, kFlatSteelNu = 0.3;

// Two steel spheres side by side on a 300 K floor, in air (surrounding layer), flattening f.
Scene two_spheres_on_a_floor(double flattening) {
  const std::string text = steel_scene()
                               .set({{"effects.gas_conduction", true},
                                     {"fluid.model", "surrounding_layer"},
                                     {"thermal.contact_flattening", flattening}})
                               .add("particle", particle({0.0, kFlatRadius_m, 0.0}))
                               .add("particle", particle({2.0 * kFlatRadius_m, kFlatRadius_m, 0.0}))
                               .add("wall", floor_wall({{"temperature", 300.0}}));
  return load_scene_text(text, "flattened.toml");
}

// The Hertz radius of the pair (R* = r/2) or of a sphere on the wall (R* = r) under F, m.
double hertz_radius_m(double R_star_m, double F_N) {
  const double E_star = 1.0 / (2.0 * (1.0 - kFlatSteelNu * kFlatSteelNu) / kFlatSteelE);
  return std::cbrt(3.0 * F_N * R_star_m / (4.0 * E_star));
}

TEST(FlattenedContacts, LoadedContactsConductThroughTheFlattenedSpotAndTheGasSeesIt) {
  const double F_N = 0.01;  // a_Hertz 2.7 um on the pair: below the flattened 12.5 um
  for (const double f : {0.0, 0.025}) {
    SCOPED_TRACE(f);
    const Scene scene = two_spheres_on_a_floor(f);
    const ThermalNetworkBuilder builder(scene);
    mechanics::ParticleSet geometry;
    geometry.add({0.0, kFlatRadius_m, 0.0}, kFlatRadius_m, 1.0, 0);
    geometry.add({2.0 * kFlatRadius_m, kFlatRadius_m, 0.0}, kFlatRadius_m, 1.0, 0);
    ContactList contacts;
    contacts.add(0, 1, F_N);
    contacts.add(0, mechanics::wall_code<std::int64_t>(0), F_N);
    contacts.add(1, mechanics::wall_code<std::int64_t>(0), 0.0);  // touching, unloaded: no spot
    thermal::ThermalNetwork net = builder.nodes();
    builder.build_edges(contacts, net, nullptr, &geometry);
    const double pair_m = std::max(hertz_radius_m(0.5 * kFlatRadius_m, F_N), f * 0.5 * kFlatRadius_m);
    const double wall_m = std::max(hertz_radius_m(kFlatRadius_m, F_N), f * kFlatRadius_m);
    EXPECT_NEAR(contacts.conductance_W_per_K[0], 2.0 * kFlatSteelK * pair_m, 1e-12);
    EXPECT_NEAR(contacts.conductance_W_per_K[1], 2.0 * kFlatSteelK * wall_m, 1e-12);
    EXPECT_EQ(contacts.conductance_W_per_K[2], 0.0);
    ASSERT_EQ(net.edge_count(), 1u);
    EXPECT_NEAR(net.edge_contact_radius_m[0], pair_m, 1e-15);
    ASSERT_EQ(net.wall_node.size(), 2u);
    for (std::size_t w = 0; w < 2; ++w)
      EXPECT_NEAR(net.wall_contact_radius_m[w], net.wall_node[w] == 0 ? wall_m : 0.0, 1e-15);
  }
}

}  // namespace
}  // namespace tmdem::coupling
