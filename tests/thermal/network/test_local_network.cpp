// A network split by NetworkPartition::slabs into LocalNetworks (the heating over MPI, without
// MPI): each process's local system, with its ghosts at their owners' temperatures, must give the
// heat flow and the Jacobian product of its own nodes exactly as the whole system does, the
// processes' ghost lists must match what their neighbours send, and the free particles' summed
// heat flow (what the distributed integrator integrates as boundary heat) must be the modes'
// boundary power.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "thermal/ThermalTestSupport.h"
#include "thermal/network/LocalNetwork.h"
#include "thermal/network/NetworkPartition.h"

namespace tmdem::thermal {
namespace {

const std::vector<std::string> kModes = {"contact_conduction", "wall_conduction", "convection",
                                         "heat_source", "wall_flux", "radiation",
                                         "gas_conduction"};

struct RandomBed {
  ThermalNetwork network;
  std::vector<double> xyz_m;
};

// 60 particles of radius 0.4 mm in a 6 x 2 x 2 mm box (x the longest), edges between centres
// closer than 0.9 mm (touching or a gap for the gas), an isothermal floor under the lowest, a
// flux wall over the highest, sources, one held particle, the particles' own resistance.
RandomBed random_bed() {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomBed bed;
  const std::size_t n = 60;
  auto& net = bed.network;
  net.resize_nodes(n);
  for (std::size_t i = 0; i < n; ++i) {
    bed.xyz_m.insert(bed.xyz_m.end(), {6e-3 * u(rng), 2e-3 * u(rng), 2e-3 * u(rng)});
    net.heat_capacity_J_per_K[i] = 0.01 * (1.0 + u(rng));
    net.surface_area_m2[i] = 1e-5;
    net.radius_m[i] = 4e-4;
    net.emissivity[i] = 0.5;
    net.heat_source_W[i] = i % 7 == 0 ? 0.01 : 0.0;
  }
  net.held[5] = 1;
  net.shell_resistance_K_sr_per_W.assign(n, 20.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(bed.xyz_m[3 * a + k] - bed.xyz_m[3 * b + k], 2);
      if (d2 < 0.9e-3 * 0.9e-3)
        net.add_edge(std::int32_t(a), std::int32_t(b), 1e-3 * (1.0 + u(rng)),
                     std::sqrt(d2) - 8e-4, 5e-5 * u(rng));
    }
  net.isothermal_walls = 1;
  net.flux_wall_power_W = {0.05};
  for (std::size_t i = 0; i < n; ++i) {
    if (bed.xyz_m[3 * i + 2] < 0.5e-3) net.add_wall_edge(std::int32_t(i), 350.0, 2e-3);
    if (bed.xyz_m[3 * i + 2] > 1.5e-3) net.add_flux_edge(std::int32_t(i), 0, 1e-3 * (1.0 + u(rng)));
  }
  return bed;
}

TEST(NetworkPartition, SlabsCutTheLongestAxisIntoEqualCounts) {
  const auto bed = random_bed();
  const auto p = NetworkPartition::slabs(bed.xyz_m, 3);
  ASSERT_EQ(p.ranks(), 3);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(p.owned_count(r), 20);
  for (std::int32_t row = 1; row < 60; ++row) {
    EXPECT_LE(bed.xyz_m[3 * std::size_t(p.node_at_row(row - 1))], bed.xyz_m[3 * std::size_t(p.node_at_row(row))]);
    EXPECT_EQ(p.row_of(p.node_at_row(row)), row);
  }
  EXPECT_EQ(p.owner(p.node_at_row(19)), 0);
  EXPECT_EQ(p.owner(p.node_at_row(20)), 1);
  const auto uneven = NetworkPartition::slabs(bed.xyz_m, 7);  // 60 = 4 x 9 + 3 x 8
  for (int r = 0; r < 7; ++r) EXPECT_EQ(uneven.owned_count(r), r < 4 ? 9 : 8);
}

TEST(LocalNetwork, GhostsAreWhatTheirOwnersSend) {
  const auto bed = random_bed();
  const auto p = NetworkPartition::slabs(bed.xyz_m, 3);
  std::vector<LocalNetwork> local;
  for (int r = 0; r < 3; ++r) local.push_back(extract_local_network(bed.network, p, r));
  std::size_t ghosts = 0;
  for (int r = 0; r < 3; ++r)
    for (const auto& n : local[std::size_t(r)].neighbours) {
      const auto& other = local[std::size_t(n.rank)];
      const auto back = std::find_if(other.neighbours.begin(), other.neighbours.end(),
                                     [&](const GhostNeighbour& m) { return m.rank == r; });
      ASSERT_NE(back, other.neighbours.end());
      std::vector<std::int32_t> sent, received;
      for (const auto k : back->send) sent.push_back(other.node[std::size_t(k)]);
      for (auto k = n.ghost_begin; k < n.ghost_end; ++k) received.push_back(local[std::size_t(r)].node[std::size_t(k)]);
      EXPECT_EQ(sent, received);
      ghosts += received.size();
    }
  EXPECT_GT(ghosts, 0u);  // the slabs do cut contacts
  // Every edge is in the local network of each process that owns one of its ends.
  std::size_t edges = 0;
  for (const auto& l : local) edges += l.network.edge_count();
  std::size_t cut = 0;
  for (std::size_t e = 0; e < bed.network.edge_count(); ++e)
    cut += p.owner(bed.network.edge_a[e]) != p.owner(bed.network.edge_b[e]);
  EXPECT_EQ(edges, bed.network.edge_count() + cut);
}

TEST(LocalNetwork, OwnedHeatFlowAndJacobianProductAreTheWholeSystems) {
  const auto bed = random_bed();
  const auto whole = testing::make_system(bed.network, kModes);
  ASSERT_EQ(whole->modes().size(), kModes.size());
  ASSERT_LT(whole->network().edge_factor(0), 0.99);  // the shells in series with the pair paths
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(280.0, 400.0);
  std::vector<double> T(60), v(60), q(60), Jv(60), scale(60);
  for (auto& x : T) x = u(rng);
  for (auto& x : v) x = u(rng) - 340.0;
  for (std::size_t i = 0; i < 60; ++i) scale[i] = std::sqrt(bed.network.heat_capacity_J_per_K[i]);
  double boundary_W = 0.0;
  ASSERT_TRUE(whole->heat_flow(T, q, boundary_W));
  JacobianEvaluation J;
  whole->evaluate_jacobian(T, J);
  whole->jacobian_times(J, v, Jv, scale);
  double q_scale = 0.0, Jv_scale = 0.0, free_sum_W = 0.0;
  for (std::size_t i = 0; i < 60; ++i) {
    q_scale = std::max(q_scale, std::abs(q[i]));
    Jv_scale = std::max(Jv_scale, std::abs(Jv[i]));
  }

  const auto p = NetworkPartition::slabs(bed.xyz_m, 3);
  std::size_t checked = 0;
  for (int r = 0; r < 3; ++r) {
    const auto local = extract_local_network(bed.network, p, r);
    const auto part = testing::make_system(local.network, kModes);
    const std::size_t n = local.node.size();
    std::vector<double> T_local(n), v_local(n), s_local(n), q_local(n), Jv_local(n);
    for (std::size_t k = 0; k < n; ++k) {
      const auto i = std::size_t(local.node[k]);
      T_local[k] = T[i];
      v_local[k] = v[i];
      s_local[k] = scale[i];
    }
    double local_boundary_W = 0.0;
    ASSERT_TRUE(part->heat_flow(T_local, q_local, local_boundary_W));
    JacobianEvaluation J_local;
    part->evaluate_jacobian(T_local, J_local);
    part->jacobian_times(J_local, v_local, Jv_local, s_local);
    for (std::size_t k = 0; k < local.owned; ++k, ++checked) {
      const auto i = std::size_t(local.node[k]);
      EXPECT_NEAR(q_local[k], q[i], 1e-13 * q_scale) << "rank " << r << " node " << i;
      EXPECT_NEAR(Jv_local[k], Jv[i], 1e-13 * Jv_scale) << "rank " << r << " node " << i;
      if (!local.network.held[k]) free_sum_W += q_local[k];
    }
  }
  EXPECT_EQ(checked, 60u);
  // The pair flows between free particles cancel: what the free particles gain is the power
  // from outside them, which the modes count as boundary power.
  EXPECT_NEAR(free_sum_W, boundary_W, 1e-13 * q_scale * 60);
  EXPECT_GT(std::abs(boundary_W), 0.01);
}

TEST(LocalNetwork, RefusesAMovingPackingsDissipation) {
  auto bed = random_bed();
  bed.network.add_dissipation(0, 1, 1.0);
  const auto p = NetworkPartition::slabs(bed.xyz_m, 2);
  EXPECT_THROW(extract_local_network(bed.network, p, 0), std::invalid_argument);
}

}  // namespace
}  // namespace tmdem::thermal
