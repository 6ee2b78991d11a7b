// A frozen bed's local set-up over MPI (coupling/run/BedPiece.h), without MPI: each process's
// piece of the bed (its own particles and those within the halo of its slab, their contacts
// and near pairs detected among those alone) must give the local network the whole bed's
// network gives (thermal::extract_local_network on it, itself tested against the whole system
// in tests/thermal/network/test_local_network.cpp): the same nodes, rows, ghosts and exchanges,
// the same edges with the same conductances, gaps and shadowing, the same wall and flux edges
// and flux powers; on a periodic lattice, a deposited bed with near pairs, and an imported
// column with its pair forces. And a piece must be a piece: fewer particles than the bed.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/run/BedPiece.h"
#include "coupling/run/PieceDiagnostics.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"
#include "support/ScratchDir.h"
#include "thermal/network/LocalNetwork.h"
#include "thermal/network/NetworkPartition.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

void expect_same_local_network(const thermal::LocalNetwork& piece,
                               const thermal::LocalNetwork& whole) {
  EXPECT_EQ(piece.owned, whole.owned);
  EXPECT_EQ(piece.node, whole.node);
  EXPECT_EQ(piece.row, whole.row);
  ASSERT_EQ(piece.neighbours.size(), whole.neighbours.size());
  for (std::size_t k = 0; k < whole.neighbours.size(); ++k) {
    EXPECT_EQ(piece.neighbours[k].rank, whole.neighbours[k].rank);
    EXPECT_EQ(piece.neighbours[k].send, whole.neighbours[k].send);
    EXPECT_EQ(piece.neighbours[k].ghost_begin, whole.neighbours[k].ghost_begin);
    EXPECT_EQ(piece.neighbours[k].ghost_end, whole.neighbours[k].ghost_end);
  }
  const auto& p = piece.network;
  const auto& w = whole.network;
  EXPECT_EQ(p.heat_capacity_J_per_K, w.heat_capacity_J_per_K);
  EXPECT_EQ(p.radius_m, w.radius_m);
  EXPECT_EQ(p.held, w.held);
  EXPECT_EQ(p.heat_source_W, w.heat_source_W);
  // Edges in the same (canonical) order, with the same values to the bit: the same builder
  // computed them from the same two particles.
  EXPECT_EQ(p.edge_a, w.edge_a);
  EXPECT_EQ(p.edge_b, w.edge_b);
  EXPECT_EQ(p.edge_conductance_W_per_K, w.edge_conductance_W_per_K);
  EXPECT_EQ(p.edge_gap_m, w.edge_gap_m);
  EXPECT_EQ(p.edge_contact_radius_m, w.edge_contact_radius_m);
  EXPECT_EQ(p.edge_in_contact, w.edge_in_contact);
  EXPECT_EQ(p.edge_shadowed, w.edge_shadowed);
  EXPECT_EQ(p.wall_node, w.wall_node);
  EXPECT_EQ(p.wall_conductance_W_per_K, w.wall_conductance_W_per_K);
  EXPECT_EQ(p.wall_gap_m, w.wall_gap_m);
  EXPECT_EQ(p.flux_node, w.flux_node);
  EXPECT_EQ(p.flux_conductance_W_per_K, w.flux_conductance_W_per_K);
  // The flux walls' conductances are summed per process, then over them: round-off.
  ASSERT_EQ(p.flux_wall_power_W.size(), w.flux_wall_power_W.size());
  for (std::size_t f = 0; f < w.flux_wall_power_W.size(); ++f)
    EXPECT_NEAR(p.flux_wall_power_W[f], w.flux_wall_power_W[f],
                1e-14 * std::abs(w.flux_wall_power_W[f]));
}

// What the processes' local networks hold, over all processes.
struct SplitCounts {
  std::size_t ghosts = 0, near_edges = 0, shadowed_edges = 0;
};

// The scene split over `ranks` processes both ways.
SplitCounts compare_piece_and_whole(const Scene& scene, int ranks) {
  std::ostringstream sink;
  ProgressReporter progress(sink, true, false);
  const auto problem = build_frozen_thermal_problem(scene, progress);
  std::vector<double> centre_m;
  for (const auto& x : problem.positions_m) centre_m.insert(centre_m.end(), x.begin(), x.end());
  const auto partition = thermal::NetworkPartition::slabs(centre_m, ranks);
  std::vector<BedPiece> pieces;
  std::vector<double> total_W_per_K;
  for (int r = 0; r < ranks; ++r) {
    pieces.push_back(BedPiece::build(scene, centre_m, partition, r));
    const auto mine = thermal::owned_flux_conductance_W_per_K(pieces.back().network,
                                                              pieces.back().particle, partition, r);
    total_W_per_K.resize(mine.size(), 0.0);
    for (std::size_t f = 0; f < mine.size(); ++f) total_W_per_K[f] += mine[f];
  }
  // The start-up diagnostics from the processes' own particles, combined: the whole bed's.
  std::vector<ThermalDiagnostics> shares;
  for (const auto& piece : pieces) shares.push_back(piece.diagnostics);
  const auto split = combine_shares(shares);
  const auto whole = diagnose(scene, problem.contacts, *problem.system, 400.0);
  EXPECT_GT(whole.heat_carrying_contacts, 0u);
  EXPECT_EQ(split.heat_carrying_contacts, whole.heat_carrying_contacts);
  EXPECT_EQ(split.isolated_particles, whole.isolated_particles);
  EXPECT_EQ(split.max_biot, whole.max_biot);
  EXPECT_EQ(split.min_time_constant_s, whole.min_time_constant_s);
  EXPECT_EQ(split.max_time_constant_s, whole.max_time_constant_s);
  SplitCounts counts;
  for (int r = 0; r < ranks; ++r) {
    SCOPED_TRACE("rank " + std::to_string(r));
    const auto& piece = pieces[std::size_t(r)];
    EXPECT_LT(piece.particle.size(), scene.particles.size());  // not the whole bed
    EXPECT_GT(piece.particle.size(), std::size_t(partition.owned_count(r)));  // a halo
    const auto from_piece = thermal::extract_local_network(piece.network, piece.particle,
                                                           partition, r, total_W_per_K);
    const auto from_whole = thermal::extract_local_network(problem.system->network(), partition, r);
    expect_same_local_network(from_piece, from_whole);
    counts.ghosts += from_whole.node.size() - from_whole.owned;
    const auto& net = from_whole.network;
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      counts.near_edges += net.edge_in_contact[e] == 0;
      counts.shadowed_edges += !net.edge_shadowed.empty() && net.edge_shadowed[e] != 0;
    }
  }
  return counts;
}

// A 10 x 6 x 6 lattice of touching spheres, periodic across x (the cut axis: the first and the
// last slab are neighbours round the boundary), an isothermal floor and a flux lid.
TEST(BedPiece, PeriodicLatticeGivesTheWholeNetworksLocalNetworks) {
  const std::string text =
      thermal_scene()
          .set({{"periodic.x", {0.0, 0.02}}, {"effects.convection", true}})
          .add("generate", lattice({10, 6, 6}))
          .add("wall", plane_wall({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {{"temperature", 400.0}}))
          .add("wall", plane_wall({0.0, 0.0, 0.012}, {0.0, 0.0, -1.0},
                                  {{"heat_flux", -2000.0}, {"heat_flux_area", 2.4e-4}}));
  const auto scene = load_scene_text(text, "lattice");
  // Three slabs of 120: each cut (two inner, one round the boundary) has 36 pairs, whose ends
  // are ghosts on the other side.
  EXPECT_EQ(compare_piece_and_whole(scene, 3).ghosts, 3u * 2u * 36u);
}

// An irregular bed: 300 spheres of two radii dropped into a box 60 mm long, with gas across gaps
// up to the smaller radius and radiation across gaps up to 4 times it (near pairs, shadowed by a
// third particle: the halo is 12 largest radii), on an isothermal floor under a flux lid.
TEST(BedPiece, DepositedBedWithNearPairsGivesTheWholeNetworksLocalNetworks) {
  const std::string text =
      thermal_scene()
          .set({{"simulation.gravity", {0.0, 0.0, -9.81}},
                {"effects.gas_conduction", true},
                {"fluid.model", "surrounding_layer"},
                {"fluid.cutoff", 1.0},
                {"effects.radiation", true},
                {"radiation.between_particles", true},
                {"radiation.surroundings", false},
                {"radiation.pair_cutoff", 4.0}})
          .add("generate", {{"kind", "deposit"},
                            {"count", 300},
                            {"box", raw("{ min = [0.0, 0.0, 0.0], max = [0.06, 0.008, 0.016] }")},
                            {"radii", {0.0006, 0.001}},
                            {"fractions", {0.5, 0.5}},
                            {"material", "steel"}})
          .add("wall", plane_wall({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {{"temperature", 400.0}}))
          .add("wall", plane_wall({0.0, 0.0, 0.016}, {0.0, 0.0, -1.0},
                                  {{"heat_flux", -2000.0}, {"heat_flux_area", 2.4e-4}}));
  const auto scene = load_scene_text(text, "deposit");
  for (const int ranks : {2, 3}) {
    SCOPED_TRACE(std::to_string(ranks) + " processes");
    const auto counts = compare_piece_and_whole(scene, ranks);
    EXPECT_GT(counts.ghosts, 0u);
    EXPECT_GT(counts.near_edges, 0u);      // the gap modes' pairs are there
    EXPECT_GT(counts.shadowed_edges, 0u);  // and some of them shadowed
  }
}

// An imported column with its pair forces (a LIGGGHTS particle dump and local dump: ten 1 mm
// steel spheres stacked along y on a hot floor, each contact carrying the weight above it): the
// Hertz conductances come from the file's forces, and the floor's from the bottom sphere's
// balance of its weight and its imported pair forces, which the process owning it must hold
// whole. Cut across y into 3 slabs, each with its halo of neighbours.
TEST(BedPiece, ImportedColumnWithItsForcesGivesTheWholeNetworksLocalNetworks) {
  const int n = 10;
  const double weight_N = 7800.0 * 4.0 / 3.0 * 3.141592653589793 * 1e-9 * 9.81;
  std::string particles = "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n" + std::to_string(n) +
                          "\nITEM: BOX BOUNDS ff ff ff\n-0.01 0.01\n0 0.03\n-0.01 0.01\n"
                          "ITEM: ATOMS id type x y z radius\n";
  std::string pairs = "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ENTRIES\n" + std::to_string(n - 1) +
                      "\nITEM: BOX BOUNDS ff ff ff\n-0.01 0.01\n0 0.03\n-0.01 0.01\nITEM: ENTRIES";
  for (int k = 1; k <= 12; ++k) pairs += " c_pc[" + std::to_string(k) + "]";
  pairs += "\n";
  char line[200];
  for (int k = 1; k <= n; ++k) {
    std::snprintf(line, sizeof line, "%d 1 0 %.17g 0 0.001\n", k, 0.002 * k - 0.001);
    particles += line;
  }
  // Upper sphere k + 1 first; the force on it is up, the weight of it and those above.
  for (int k = 1; k < n; ++k) {
    std::snprintf(line, sizeof line, "0 %.17g 0 0 %.17g 0 %d %d 0 0 %.17g 0\n",
                  0.002 * (k + 1) - 0.001, 0.002 * k - 0.001, k + 1, k, (n - k) * weight_N);
    pairs += line;
  }
  const auto dir = tmdem::test::scratch_folder("tmdem_bed_piece_", "imported");
  std::ofstream(dir + "/column.dump") << particles;
  std::ofstream(dir + "/pairs.dump") << pairs;
  const std::string text =
      steel_scene()
          .set({{"simulation.gravity", {0.0, -9.81, 0.0}}, {"effects.mechanics", "off"}})
          .add("import", {{"file", dir + "/column.dump"},
                          {"material", "steel"},
                          {"contacts", dir + "/pairs.dump"},
                          {"contact_columns",
                           raw("{ id1 = \"c_pc[7]\", id2 = \"c_pc[8]\", force = [\"c_pc[10]\", "
                               "\"c_pc[11]\", \"c_pc[12]\"] }")}})
          .add("wall", floor_wall({{"temperature", 373.15}}));
  std::ofstream(dir + "/column.toml") << text;
  const auto scene = load_scene_file(dir + "/column.toml");
  ASSERT_EQ(scene.imported_forces.pairs.size(), std::size_t(n - 1));
  // Two cuts of one pair each, both ends ghosts on the other side.
  EXPECT_EQ(compare_piece_and_whole(scene, 3).ghosts, 4u);
}

}  // namespace
}  // namespace tmdem::coupling
