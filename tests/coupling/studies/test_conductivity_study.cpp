// `tmdem study conductivity` (coupling/studies/ConductivityStudy.h) against hand-computed
// series resistances, a long transient run and the heat balance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"
#include "coupling/studies/ConductivityStudy.h"
#include "support/SceneBuilder.h"
#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/system/JacobianEvaluation.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

constexpr double kH = 1.0e-3;  // W/K, every contact (thermal_scene)
constexpr double kD = 0.002;   // m, sphere diameter (lattice)

// nx x ny x nz simple cubic lattice of touching spheres between a hot floor (y = 0) and a cold
// lid touching the top layer (y = ny d).
std::string lattice_between_walls(int nx, int ny, int nz, double T_hot, double T_cold) {
  return thermal_scene()
      .add("generate", lattice({nx, ny, nz}, {{"temperature", 300.0}}))
      .add("wall", floor_wall({{"temperature", T_hot}}))
      .add("wall", plane_wall({0.0, ny * kD, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", T_cold}}))
      .str();
}

// The same in air (surrounding-layer gas), the lid `lid_gap_m` above the top layer.
std::string lattice_in_air(int nx, int ny, int nz, double lid_gap_m) {
  return SceneBuilder(thermal_scene())
      .set("effects.gas_conduction", true)
      .set("fluid.model", "surrounding_layer")
      .add("generate", lattice({nx, ny, nz}, {{"temperature", 300.0}}))
      .add("wall", floor_wall({{"temperature", 310.0}}))
      .add("wall", plane_wall({0.0, ny * kD + lid_gap_m, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 290.0}}))
      .str();
}

ProgressReporter quiet_progress() {
  static std::ostringstream sink;
  return ProgressReporter(sink, true, false);
}

// Every column of the lattice a chain of n_y - 1 sphere pairs (G_pp) and two wall pairs (G_w):
// k_eff = n_y / (d ((n_y - 1) / G_pp + 2 / G_w)); heat in equals heat out, the shares add to 1.
void expect_chain_of_columns(const ConductivityResult& r, int ny, double G_pp, double G_w,
                             double tolerance) {
  const double expected = ny / (kD * ((ny - 1) / G_pp + 2.0 / G_w));
  EXPECT_NEAR(r.k_eff_W_per_mK, expected, tolerance * expected);
  EXPECT_LE(r.balance_rel, 1e-12);
  double sum = 0.0;
  for (const auto& m : r.modes) sum += m.share;
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

// Each column is ny + 1 equal contacts in series (wall, ny - 1 between spheres, wall):
// Q = nx nz H dT / (ny + 1), L = ny d, A = nx nz d^2, so k_eff = H / d * ny / (ny + 1).
TEST(ConductivityStudy, SimpleCubicLatticeIsSeriesResistances) {
  for (const auto& [nx, ny, nz] : {std::tuple{4, 6, 4}, std::tuple{3, 2, 5}, std::tuple{1, 9, 1}}) {
    const auto scene = load_scene_text(lattice_between_walls(nx, ny, nz, 310.0, 290.0), "lattice");
    auto progress = quiet_progress();
    const auto r = run_conductivity_study(scene, progress);
    const double expected = kH / kD * ny / (ny + 1.0);
    EXPECT_NEAR(r.k_eff_W_per_mK, expected, 1e-12 * expected) << nx << "x" << ny << "x" << nz;
    EXPECT_NEAR(r.heat_hot_W, nx * nz * kH * 20.0 / (ny + 1.0), 1e-13);
    // Heat in = heat out to round-off.
    EXPECT_LE(r.balance_rel, 1e-13);
    EXPECT_NEAR(r.length_m, ny * kD, 1e-15);
    EXPECT_NEAR(r.area_m2, nx * nz * kD * kD, 1e-18);
    EXPECT_NEAR(r.porosity, 1.0 - std::numbers::pi / 6.0, 1e-12);
    const int pairs = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
    EXPECT_EQ(r.contacts, std::size_t(pairs));
    EXPECT_EQ(r.wall_contacts, std::size_t(2 * nx * nz));
    EXPECT_DOUBLE_EQ(r.coordination, 2.0 * pairs / (nx * ny * nz));
    // Shares: sphere-sphere contacts span L - d of the bed, the two wall contacts d / 2 each.
    ASSERT_EQ(r.modes.size(), 2u);
    EXPECT_EQ(r.modes[0].mode, "contact_conduction");
    EXPECT_NEAR(r.modes[0].share, (ny - 1.0) / ny, 1e-12);
    EXPECT_NEAR(r.modes[1].share, 1.0 / ny, 1e-12);
    EXPECT_EQ(r.floating_particles, 0u);
    // Linear profile: layer k (from the floor) at T_hot - (k + 1) dT / (ny + 1).
    for (std::size_t i = 0; i < r.T_K.size(); ++i) {
      const int k = int(i) / nx % ny;
      EXPECT_NEAR(r.T_K[i], 310.0 - (k + 1) * 20.0 / (ny + 1.0), 1e-10) << "particle " << i;
    }
  }
}

// The bulk (centres more than two diameters from both walls) of a simple cubic lattice: the
// layers between the planes at 2 d and L - 2 d, whole spheres (the planes fall between layers),
// so porosity_bulk = 1 - pi/6, and the interior gradient dT/d per layer of H dT per column:
// k_bulk = H / d exactly, without the two wall contacts that k_eff = H / d n_y / (n_y + 1) has.
TEST(ConductivityStudy, BulkOfALatticeLeavesTheWallContactsOut) {
  const int nx = 4, ny = 10, nz = 3;
  auto progress = quiet_progress();
  const auto r = run_conductivity_study(
      load_scene_text(lattice_between_walls(nx, ny, nz, 310.0, 290.0), "bulk"), progress);
  EXPECT_NEAR(r.bulk_margin_m, 2.0 * kD, 1e-15);
  EXPECT_EQ(r.bulk_particles, std::size_t(nx * nz * (ny - 4)));
  ASSERT_TRUE(r.k_bulk_W_per_mK && r.porosity_bulk);
  EXPECT_NEAR(*r.k_bulk_W_per_mK, kH / kD, 1e-9 * kH / kD);
  EXPECT_NEAR(r.k_eff_W_per_mK, kH / kD * ny / (ny + 1.0), 1e-12 * kH / kD);
  EXPECT_NEAR(*r.porosity_bulk, 1.0 - std::numbers::pi / 6.0, 1e-12);
  EXPECT_FALSE(r.zsb_bulk_W_per_mK);  // no gas: no ZSB
  // Too thin a bed for a bulk (fewer than 20 particles beyond the margins): none.
  const auto thin = run_conductivity_study(
      load_scene_text(lattice_between_walls(3, 5, 3, 310.0, 290.0), "thin"), progress);
  EXPECT_EQ(thin.bulk_particles, 9u);
  EXPECT_FALSE(thin.k_bulk_W_per_mK);
  EXPECT_FALSE(thin.porosity_bulk);
}

// The steady state agrees with a long CVODE run of the same scene (integrated far past the
// slowest time constant) to the integrator's tolerance.
TEST(ConductivityStudy, SteadyStateMatchesLongTransient) {
  const auto scene = load_scene_text(lattice_between_walls(3, 5, 2, 330.0, 280.0), "lattice");
  auto progress = quiet_progress();
  const auto r = run_conductivity_study(scene, progress);
  auto problem = build_frozen_thermal_problem(scene, progress);
  thermal::IntegratorSettings settings;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance_K = 1e-10;
  settings.max_temperature_K = 330.0;
  auto cvode = thermal::make_thermal_integrator("cvode", *problem.system, settings);
  cvode->initialize(0.0, problem.T0_K);
  // Steel, C = m c = 0.0150 J/K per sphere, H = 1 mW/K: the slowest mode of a column of 5
  // decays in about 110 s; 20,000 s leaves exp(-180) of the start.
  cvode->advance_to(20000.0);
  const auto T = cvode->temperatures_K();
  double worst = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) worst = std::max(worst, std::abs(T[i] - r.T_K[i]));
  EXPECT_LT(worst, 1e-7);  // K: rtol 1e-10 x 330 K, accumulated over the run
  std::cout << "largest |T_cvode - T_steady| = " << worst << " K\n";
}

// A column of n spheres on the axis of an (adiabatic) cylinder of radius R_c between a hot floor
// and a cold lid: Q = H dT / (n + 1), L = n d and A = pi R_c^2 (the cylinder bounds the
// cross-section), so k_eff = H n d / ((n + 1) pi R_c^2).
TEST(ConductivityStudy, ColumnInACylinderUsesItsCrossSection) {
  const int n = 5;
  const double Rc = 0.0015;
  const auto text = thermal_scene()
                        .add("generate", lattice({1, n, 1}, {{"origin", {0.0, 0.001, 0.0}}}))
                        .add("wall", floor_wall({{"temperature", 320.0}}))
                        .add("wall", plane_wall({0.0, n * kD, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 300.0}}))
                        .add("wall", {{"shape", "cylinder"}, {"point", {0.0, 0.0, 0.0}},
                                      {"axis", {0.0, 1.0, 0.0}}, {"radius", Rc}, {"material", "steel"}})
                        .str();
  auto progress = quiet_progress();
  const auto r = run_conductivity_study(load_scene_text(text, "column"), progress);
  const double expected = kH * n * kD / ((n + 1) * std::numbers::pi * Rc * Rc);
  EXPECT_NEAR(r.area_m2, std::numbers::pi * Rc * Rc, 1e-18);
  EXPECT_NEAR(r.k_eff_W_per_mK, expected, 1e-12 * expected);
  EXPECT_LE(r.balance_rel, 1e-13);
}

// With gas in the gaps the lattice is still series resistances, now of the contact plus gas
// conductances the modes assign (read back from the system's Jacobian: G_pp per sphere pair,
// G_w per sphere-wall pair): k_eff = n_y / (d ((n_y - 1) / G_pp + 2 / G_w)). The shares of
// contact, wall and gas conduction add up to 1 and heat in equals heat out.
TEST(ConductivityStudy, LatticeInAirIsSeriesOfContactPlusGas) {
  const int nx = 3, ny = 4, nz = 2;
  const auto scene = load_scene_text(lattice_in_air(nx, ny, nz, 0.0), "air");
  auto progress = quiet_progress();
  const auto r = run_conductivity_study(scene, progress);
  auto problem = build_frozen_thermal_problem(scene, progress);
  thermal::JacobianEvaluation J;
  problem.system->evaluate_jacobian(problem.T0_K, J);
  const auto& net = problem.system->network();
  double G_pp = 0.0;
  int node0_edges = 0;
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    if (net.edge_a[e] != 0 && net.edge_b[e] != 0) continue;
    G_pp = J.edge_W_per_K[e];  // the same for every touching pair of the lattice
    ++node0_edges;
  }
  ASSERT_EQ(node0_edges, 3);  // the floor corner touches 3 spheres
  ASSERT_GT(G_pp, kH);        // the gas adds to the contact
  const double G_w = -J.diagonal_W_per_K[0] - 3.0 * G_pp;
  expect_chain_of_columns(r, ny, G_pp, G_w, 1e-12);
  const auto gas = std::find_if(r.modes.begin(), r.modes.end(),
                                [](const ModeShare& m) { return m.mode == "gas_conduction"; });
  ASSERT_NE(gas, r.modes.end());
  EXPECT_GT(gas->share, 0.0);
  EXPECT_GT(gas->hot_wall_W, 0.0);
}

// A lid 0.1 R above the top layer touches nothing, so all its heat crosses the gas gap: its
// wall edges are near pairs, not contacts (the study once counted only contacts and stopped
// with a logic error). Heat in equals heat out and the shares add up to 1.
TEST(ConductivityStudy, LidAcrossAGasGapCarriesHeat) {
  auto progress = quiet_progress();
  const auto r = run_conductivity_study(load_scene_text(lattice_in_air(2, 3, 2, 1e-4), "gap"), progress);
  EXPECT_EQ(r.cold_wall_contacts, 0u);
  EXPECT_GT(r.heat_cold_W, 0.0);
  EXPECT_LE(r.balance_rel, 1e-12);
  double sum = 0.0;
  for (const auto& m : r.modes) sum += m.share;
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

// The particle's own resistance (thermal.particle_resistance = "isothermal_core"): every column
// is still a chain, now of H'_pp = 1 / (1/H_pp + 2 R) between spheres and H'_w = 1 / (1/H_w + R)
// at the walls, R = (1/(c r) - 1/r) / (k Omega) with the 30 degree cone of an equal touching
// sphere (the mirror image at a wall), Omega = 2 pi (1 - cos 30 deg). Without gas H_pp = H_w = H;
// with the surrounding layer each pair adds its H_g before the shells are put in series. The
// lateral contacts carry nothing (every column alike), so k_eff = n_y / (d ((n_y - 1) / H'_pp +
// 2 / H'_w)) exactly.
TEST(ConductivityStudy, ParticleResistanceIsInSeriesWithEachPair) {
  const int nx = 4, ny = 6, nz = 4;
  const double k = 1.0, r = 0.5 * kD, theta = std::numbers::pi / 6.0;
  for (const double c : {0.5, 0.3}) {
    for (const bool air : {false, true}) {
      SCOPED_TRACE(std::string(air ? "air" : "vacuum") + ", c = " + std::to_string(c));
      auto text = SceneBuilder()
                      .set("simulation.duration", 1.0)
                      .add("material", steel({{"conductivity", k}}))
                      .set({{"effects.mechanics", "off"},
                            {"thermal.conductance", "constant"},
                            {"thermal.constant_conductance", kH},
                            {"thermal.particle_resistance", "isothermal_core"},
                            {"thermal.core_fraction", c}})
                      .add("generate", lattice({nx, ny, nz}, {{"temperature", 300.0}}))
                      .add("wall", floor_wall({{"temperature", 310.0}}))
                      .add("wall", plane_wall({0.0, ny * kD, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 290.0}}));
      if (air) text.set({{"effects.gas_conduction", true}, {"fluid.model", "surrounding_layer"}});
      auto progress = quiet_progress();
      const auto result = run_conductivity_study(load_scene_text(text.str(), "resist"), progress);
      const double R = (1.0 / (c * r) - 1.0 / r) / (k * 2.0 * std::numbers::pi * (1.0 - std::cos(theta)));
      // Gas across a touching pair and a touching sphere-plane (defaults: k_f 0.0262, layer
      // 0.4 r, L_min 1e-7 m; constant law: no contact disc).
      const double Hg_pp =
          air ? thermal::surrounding_layer_conductance_W_per_K({r, r, 0.0, 0.0}, 0.0262, 0.4, 1e-7) : 0.0;
      thermal::GasGap plane;
      plane.radius_a_m = r;
      const double Hg_w = air ? thermal::surrounding_layer_conductance_W_per_K(plane, 0.0262, 0.4, 1e-7) : 0.0;
      const double G_pp = 1.0 / (1.0 / (kH + Hg_pp) + 2.0 * R), G_w = 1.0 / (1.0 / (kH + Hg_w) + R);
      expect_chain_of_columns(result, ny, G_pp, G_w, 1e-11);
      if (!air) {
        // Off, the same lattice gives today's H / d n_y / (n_y + 1): the shells cost this much.
        EXPECT_LT(result.k_eff_W_per_mK, 0.6 * kH / kD * ny / (ny + 1.0));
      }
    }
  }
}

TEST(ConductivityStudy, RefusesScenesWithoutTwoFacingIsothermalWalls) {
  const auto one_wall = thermal_scene()
                            .add("generate", lattice({2, 2, 2}))
                            .add("wall", floor_wall({{"temperature", 300.0}}))
                            .add("wall", plane_wall({0.0, 0.004, 0.0}, {0.0, -1.0, 0.0}))
                            .str();
  try {
    conductivity_walls(load_scene_text(one_wall, "one"));
    FAIL() << "accepted one isothermal wall";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("exactly two walls"), std::string::npos) << e.what();
  }
  const auto parallel = thermal_scene()
                            .add("generate", lattice({2, 2, 2}))
                            .add("wall", floor_wall({{"temperature", 300.0}}))
                            .add("wall", plane_wall({0.0, 0.004, 0.0}, {1.0, 0.0, 0.0},
                                                    {{"temperature", 290.0}}))
                            .str();
  EXPECT_THROW(conductivity_walls(load_scene_text(parallel, "parallel")), SceneError);
  EXPECT_THROW(conductivity_walls(load_scene_text(lattice_between_walls(2, 2, 2, 300.0, 300.0), "eq")),
               SceneError);
  // The hot wall is the warmer one, whatever the order in the file.
  const auto walls = conductivity_walls(load_scene_text(lattice_between_walls(2, 2, 2, 280.0, 300.0), "rev"));
  EXPECT_EQ(walls.first, 1u);
  EXPECT_EQ(walls.second, 0u);
}

}  // namespace
}  // namespace tmdem::coupling
