// The gas_conduction mode's layer_share = "equal_solid_angle": each pair's share of the
// surrounding layer (simple cubic and fcc nodes, walls, solid angles) and its use by the
// particle-resistance mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/GasGapCases.h"
#include "thermal/modes/ParticleResistance.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;
using namespace tmdem::thermal::gas_test;

// fluid.layer_share = "equal_solid_angle": a particle with z pairs inside the layer gives each
// the cone of solid angle 4 pi / z around the pair's axis; the pair's disk ends where the
// smaller of its two cones meets the particle's surface (docs/heat-modes.md "Gas in the gaps").
namespace {

// The equal-spheres closed form of the layer integral (k_f = 1) from the contact radius a out
// to a given disk radius r_hi (no layer-sphere intersection: r_hi is the caller's).
double equal_spheres_to(double R, double gap, double a, double L, double r_hi) {
  const double D = 2.0 * R + gap;
  const double u_k = 0.5 * (D - L);
  const double r_k = u_k < R ? std::clamp(std::sqrt(R * R - u_k * u_k), a, r_hi) : a;
  const auto F = [&](double r) {
    const double u = std::sqrt(R * R - r * r);
    return -0.5 * u - 0.25 * D * std::log(D - 2.0 * u);
  };
  return kPi * (r_k * r_k - a * a) / L + 2.0 * kPi * (F(r_k) - F(r_hi));
}

// Where the layer (thickness f R around one of two equal spheres at centre distance D) meets
// the other: the unshared disk radius, by the triangle of the two centres.
double layer_edge(double R, double D, double f) {
  const double P = (1.0 + f) * R;
  if (D * D <= P * P - R * R) return R;
  const double x = (D * D + P * P - R * R) / (2.0 * D);
  return std::min(R, std::sqrt(P * P - x * x));
}

struct Cluster {
  std::vector<std::array<double, 3>> x;
  ThermalNetwork net;
};

// Equal spheres of radius kR at the given centres (units of kR); an edge for every pair up to a
// gap of 1.2 R (beyond any layer here, so some edges must not count).
Cluster cluster(const std::vector<std::array<double, 3>>& centres) {
  Cluster c;
  for (const auto& p : centres) c.x.push_back({p[0] * kR, p[1] * kR, p[2] * kR});
  c.net.resize_nodes(c.x.size());
  c.net.heat_capacity_J_per_K.assign(c.x.size(), 1e-2);
  c.net.radius_m.assign(c.x.size(), kR);
  for (std::size_t i = 0; i < c.x.size(); ++i)
    for (std::size_t j = i + 1; j < c.x.size(); ++j) {
      const double d = std::hypot(c.x[i][0] - c.x[j][0], c.x[i][1] - c.x[j][1], c.x[i][2] - c.x[j][2]);
      const double gap = std::abs(d - 2.0 * kR) < 1e-12 * kR ? 0.0 : d - 2.0 * kR;
      if (gap < 1.2 * kR) c.net.add_edge(int(i), int(j), 0.0, gap, 0.0, gap <= 0.0);
    }
  return c;
}

ModeSettings shared_settings(double cutoff, bool share = true) {
  ModeSettings s;
  s.set("gas_conduction", "model", 1.0);  // surrounding_layer
  s.set("gas_conduction", "layer_share", share ? 1.0 : 0.0);
  s.set("gas_conduction", "cutoff", cutoff);
  s.set("gas_conduction", "conductivity", 1.0);
  return s;
}

// Per edge, the conductance the mode applies, read off the whole cluster's flows (the share
// depends on the neighbours): with T_a = 1 and every other node at 0, q_b = H_ab.
std::vector<double> edge_conductances(const ThermalNetwork& net, const ModeSettings& s) {
  auto sys = make_system(net, {"gas_conduction"}, s);
  std::vector<double> H(net.edge_count());
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    std::vector<double> T(net.node_count(), 0.0), q(net.node_count());
    T[net.edge_a[e]] = 1.0;
    double boundary = 0.0;
    EXPECT_TRUE(sys->heat_flow(T, q, boundary));
    H[e] = q[net.edge_b[e]];
  }
  return H;
}

std::vector<std::array<double, 3>> fcc_node() {  // the centre and its 12 nearest neighbours
  std::vector<std::array<double, 3>> p{{0, 0, 0}};
  const double s = std::sqrt(2.0);
  for (int i = 0; i < 3; ++i)
    for (const double u : {-s, s})
      for (const double v : {-s, s}) {
        std::array<double, 3> c{0, 0, 0};
        c[(i + 1) % 3] = u;
        c[(i + 2) % 3] = v;
        p.push_back(c);
      }
  return p;
}

std::vector<std::array<double, 3>> simple_cubic_node() {
  return {{0, 0, 0}, {2, 0, 0}, {-2, 0, 0}, {0, 2, 0}, {0, -2, 0}, {0, 0, 2}, {0, 0, -2}};
}

}  // namespace

TEST(GasShare, EqualShareRadiusIsTheConeOfSolidAngleFourPiOverZ) {
  EXPECT_EQ(equal_share_disk_radius_m(kR, 0), kInf);
  EXPECT_EQ(equal_share_disk_radius_m(kR, 1), kInf);  // alone with one partner: nothing to share
  EXPECT_DOUBLE_EQ(equal_share_disk_radius_m(kR, 2), kR);  // a hemisphere each
  EXPECT_DOUBLE_EQ(equal_share_disk_radius_m(kR, 6), kR * std::sqrt(5.0) / 3.0);
  EXPECT_DOUBLE_EQ(equal_share_disk_radius_m(kR, 12), kR * std::sqrt(11.0) / 6.0);
  for (const std::size_t z : {2, 3, 4, 6, 8, 12, 14}) {
    const double rho = equal_share_disk_radius_m(kR, z);
    const double cone = 2.0 * kPi * (1.0 - std::sqrt(1.0 - (rho / kR) * (rho / kR)));
    EXPECT_NEAR(cone, 4.0 * kPi / double(z), 1e-13) << z;
  }
}

TEST(GasShare, AnIsolatedPairKeepsTheWholeLayer) {
  // Nothing to share: exactly the surrounding layer, touching and near, and with one more
  // neighbour (z = 2, a hemisphere each, which the layer never exceeds).
  for (const double gap : {0.0, 0.1 * kR}) {
    ThermalNetwork net;
    net.resize_nodes(2);
    net.heat_capacity_J_per_K = {1e-2, 1e-2};
    net.radius_m = {kR, 0.7 * kR};
    net.add_edge(0, 1, 0.0, gap, gap > 0.0 ? 0.0 : 1e-5, gap <= 0.0);
    const double layer = surrounding_layer_conductance_W_per_K(
        spheres(kR, 0.7 * kR, gap, gap > 0.0 ? 0.0 : 1e-5), 1.0, kLayer, kL);
    EXPECT_EQ(edge_conductances(net, shared_settings(kLayer))[0], layer) << gap;
  }
  auto c = cluster({{0, 0, 0}, {2, 0, 0}, {-2, 0, 0}});
  const auto H = edge_conductances(c.net, shared_settings(kLayer));
  const auto none = edge_conductances(c.net, shared_settings(kLayer, false));
  for (std::size_t e = 0; e < H.size(); ++e) EXPECT_EQ(H[e], none[e]) << e;
}

TEST(GasShare, SimpleCubicNodeIsClippedOnlyWhenTheLayerReachesPastItsShare) {
  // Centre z = 6 (share radius R sqrt(5)/3 = 0.745 R). The outer six are 2 sqrt(2) R apart
  // (gap 0.83 R) from four of the others: at cutoff 0.4 outside the layer (z = 1), at cutoff
  // 1.0 inside (z = 5, share 0.8 R, beyond both their layer's edge 0.47 R and the centre's).
  auto c = cluster(simple_cubic_node());
  const double rho6 = kR * std::sqrt(5.0) / 3.0;
  // cutoff 0.4: the layer ends at 0.65 R, inside the share: unchanged.
  ASSERT_LT(layer_edge(kR, 2.0 * kR, 0.4), rho6);
  // cutoff 1.0: the layer would reach 0.968 R, clipped to 0.745 R.
  ASSERT_GT(layer_edge(kR, 2.0 * kR, 1.0), rho6);
  for (const double f : {0.4, 1.0}) {
    const auto H = edge_conductances(c.net, shared_settings(f));
    for (std::size_t e = 0; e < H.size(); ++e) {
      if (c.net.edge_a[e] != 0) {
        const double gap = c.net.edge_gap_m[e];
        EXPECT_NEAR(gap, (2.0 * std::sqrt(2.0) - 2.0) * kR, 1e-15);
        // Unclipped: the plain surrounding layer, bit for bit (0 beyond the cutoff).
        EXPECT_EQ(H[e], surrounding_layer_conductance_W_per_K(spheres(kR, kR, gap), 1.0, f, kL))
            << "outer pair " << e << " cutoff " << f;
        if (f == 1.0) {
          EXPECT_GT(H[e], 0.0);
        }
        continue;
      }
      const double expected = equal_spheres_to(kR, 0.0, 0.0, kL, std::min(layer_edge(kR, 2.0 * kR, f), rho6));
      EXPECT_NEAR(H[e] / expected, 1.0, 1e-9) << "cutoff " << f;
    }
  }
}

TEST(GasShare, AnIsothermalWallIsANeighbourAndItsDiskIsClippedToo) {
  // The simple cubic node at cutoff 1.0 with a wall touching the outer particle at x = 2 R (the
  // plane x = 3 R; every other particle 2 R or more from it): that particle has z = 6 (the
  // centre, 4 outer at gap 0.83 R, the wall), share R sqrt(5)/3. Its wall layer would reach
  // r_out = R (P = 2 R, centre 1 R from the plane), clipped to the share: the sphere-plane
  // integral to R sqrt(5)/3, u = sqrt(R^2 - r^2), S = R - u, int 2 pi r dr / max(L, S) =
  // pi r_k^2 / L + 2 pi [-u - R ln(R - u)] from r_k (S = L) to the disk's edge.
  auto c = cluster(simple_cubic_node());
  ASSERT_EQ(c.x[1][0], 2.0 * kR);
  c.net.add_wall_edge(1, 400.0, 0.0, -1, 0.0, 0.0, true);
  auto sys = make_system(c.net, {"gas_conduction"}, shared_settings(1.0));
  std::vector<double> T(c.x.size(), 0.0), q(c.x.size());
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  const double rho6 = kR * std::sqrt(5.0) / 3.0, u_k = kR - kL;
  const double r_k = std::sqrt(kR * kR - u_k * u_k);
  const auto G = [](double r) {
    const double u = std::sqrt(std::max(kR * kR - r * r, 0.0));  // r = R: 0, not a rounding below it
    return -u - kR * std::log(kR - u);
  };
  const double expected = kPi * r_k * r_k / kL + 2.0 * kPi * (G(r_k) - G(rho6));
  EXPECT_NEAR(q[1] / (400.0 * expected), 1.0, 1e-9);
  EXPECT_EQ(boundary, q[1]);
  // Without sharing the whole layer, out to r = R, conducts more.
  auto whole = make_system(c.net, {"gas_conduction"}, shared_settings(1.0, false));
  ASSERT_TRUE(whole->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[1] / (400.0 * (kPi * r_k * r_k / kL + 2.0 * kPi * (G(r_k) - G(kR)))), 1.0, 1e-9);
}

TEST(GasShare, FccNodeGetsTheTwelfthOfItsSurroundings) {
  // Centre: 12 touching neighbours, share radius R sqrt(11)/6 = 0.553 R < the layer's 0.65 R.
  // Each outer particle: the centre and 4 outer neighbours touching (the rest 2.83 R and more
  // apart), z = 5, share radius 2 R sqrt(4)/5 = 0.8 R: outer pairs keep their whole layer.
  auto c = cluster(fcc_node());
  ASSERT_EQ(c.x.size(), 13u);
  const auto H = edge_conductances(c.net, shared_settings(kLayer));
  const double rho12 = kR * std::sqrt(11.0) / 6.0, edge = layer_edge(kR, 2.0 * kR, kLayer);
  ASSERT_LT(rho12, edge);
  ASSERT_GT(0.8 * kR, edge);
  const double clipped = equal_spheres_to(kR, 0.0, 0.0, kL, rho12);
  const double whole = equal_spheres_to(kR, 0.0, 0.0, kL, edge);
  std::vector<int> touching(13, 0);
  for (std::size_t e = 0; e < H.size(); ++e) {
    if (c.net.edge_gap_m[e] > 0.0) {
      EXPECT_EQ(H[e], 0.0) << e;  // beyond the layer
      continue;
    }
    ++touching[c.net.edge_a[e]];
    ++touching[c.net.edge_b[e]];
    EXPECT_NEAR(H[e] / (c.net.edge_a[e] == 0 ? clipped : whole), 1.0, 1e-9) << e;
  }
  EXPECT_EQ(touching[0], 12);
  for (int i = 1; i < 13; ++i) EXPECT_EQ(touching[i], 5) << i;
  // The clip removes the outer rim of the layer, where the gas is thickest: 3 per cent.
  EXPECT_LT(clipped, whole);
  EXPECT_GT(clipped, 0.96 * whole);
}

TEST(GasShare, SolidAnglesNeverExceedTheSurroundingsSymmetricAndConservative) {
  // The fcc sites within 3 R of a centre (1 + 12 + 6; the 6 second neighbours are 0.83 R
  // apart, outside the layer of 0.6 R, but touch 4 of the 12), jittered to open and close some
  // gaps: z of 12, 7 and 4 and near pairs. Per pair the disk is min(layer edge, share of a,
  // share of b), z counted here by hand; the cones of a particle's pairs add up to <= 4 pi.
  std::vector<std::array<double, 3>> p{{0, 0, 0}};
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k)
        if ((i + j + k) % 2 == 0 && i * i + j * j + k * k > 0 && 2 * (i * i + j * j + k * k) < 9)
          p.push_back({std::sqrt(2.0) * i, std::sqrt(2.0) * j, std::sqrt(2.0) * k});
  ASSERT_EQ(p.size(), 19u);
  for (std::size_t i = 1; i < p.size(); ++i) p[i][0] += 0.07 * std::sin(3.0 * double(i));
  const double f = 0.6;
  auto c = cluster(p);
  const auto H = edge_conductances(c.net, shared_settings(f));
  std::vector<std::size_t> z(p.size(), 0);
  for (std::size_t e = 0; e < H.size(); ++e)
    if (c.net.edge_gap_m[e] < f * kR) ++z[c.net.edge_a[e]], ++z[c.net.edge_b[e]];
  const auto share = [&](std::size_t zi) {
    return zi <= 1 ? kInf : 2.0 * kR * std::sqrt(double(zi) - 1.0) / double(zi);
  };
  std::vector<double> solid_angle(p.size(), 0.0);
  int clipped = 0;
  for (std::size_t e = 0; e < H.size(); ++e) {
    const auto a = c.net.edge_a[e], b = c.net.edge_b[e];
    const double gap = c.net.edge_gap_m[e];
    if (!(gap < f * kR)) {
      EXPECT_EQ(H[e], 0.0);
      continue;
    }
    const double edge = layer_edge(kR, 2.0 * kR + gap, f);
    const double disk = std::min({edge, share(z[a]), share(z[b])});
    clipped += disk < edge;
    const double cone = 2.0 * kPi * (1.0 - std::sqrt(1.0 - (disk / kR) * (disk / kR)));
    solid_angle[a] += cone;
    solid_angle[b] += cone;
    const GasGap g = spheres(kR, kR, gap);
    EXPECT_NEAR(H[e] / surrounding_layer_conductance_W_per_K(g, 1.0, f, kL, 0.0, disk), 1.0, 1e-12) << e;
    EXPECT_LE(H[e], surrounding_layer_conductance_W_per_K(g, 1.0, f, kL) * (1.0 + 1e-12)) << e;
  }
  EXPECT_GT(clipped, 12);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_LE(solid_angle[i], 4.0 * kPi * (1.0 + 1e-12)) << i;
  EXPECT_NEAR(solid_angle[0], 4.0 * kPi, 1e-12);  // the centre: every one of its pairs clipped

  // Symmetric in a and b: the same pairs listed the other way round give the same conductances.
  ThermalNetwork swapped = c.net;
  std::swap(swapped.edge_a, swapped.edge_b);
  const auto Hs = edge_conductances(swapped, shared_settings(f));
  for (std::size_t e = 0; e < H.size(); ++e) EXPECT_EQ(Hs[e], H[e]) << e;

  // Conservative: the flows of an arbitrary temperature field add up to 0 (no walls).
  auto sys = make_system(c.net, {"gas_conduction"}, shared_settings(f));
  std::vector<double> T(p.size()), q(p.size());
  double sum = 0.0, scale = 0.0, boundary = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) T[i] = 300.0 + 40.0 * std::cos(1.7 * double(i));
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  for (const double qi : q) sum += qi, scale += std::abs(qi);
  EXPECT_GT(scale, 0.0);
  EXPECT_NEAR(sum, 0.0, 1e-14 * scale);
}

TEST(GasShare, SharingNeedsTheSurroundingLayer) {
  // The touching-pair closed form has no layer to clip: refused naming the key.
  ModeSettings s;
  s.set("gas_conduction", "layer_share", 1.0);
  std::string why = "accepted";
  try {
    make_heat_transfer_mode("gas_conduction", s);
  } catch (const std::invalid_argument& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("layer_share: needs model = \"surrounding_layer\""), std::string::npos) << why;
  EXPECT_NO_THROW(make_heat_transfer_mode("gas_conduction", shared_settings(kLayer)));
}

TEST(GasShare, ParticleResistanceTakesTheSharedConductance) {
  // thermal.particle_resistance: the shells (core 0.7 R, k = 1) are in series with the gas
  // conductance the mode reports, the shared one. Touching equal spheres: the partner's cone
  // has half-angle asin(R / 2R) = 30 degrees, shell (1/(c R) - 1/R) / (k 2 pi (1 - cos 30)).
  auto c = cluster(fcc_node());
  const double core = 0.7, k = 1.0;
  c.net.shell_resistance_K_sr_per_W.assign(c.x.size(), shell_resistance_K_sr_per_W(kR, k, core));
  const auto H = edge_conductances(c.net, shared_settings(kLayer));
  const double cone = 2.0 * kPi * (1.0 - std::cos(kPi / 6.0));
  const double shell = (1.0 / (core * kR) - 1.0 / kR) / (k * cone);
  const double clipped = equal_spheres_to(kR, 0.0, 0.0, kL, kR * std::sqrt(11.0) / 6.0);
  const double whole = equal_spheres_to(kR, 0.0, 0.0, kL, layer_edge(kR, 2.0 * kR, kLayer));
  for (std::size_t e = 0; e < H.size(); ++e) {
    if (c.net.edge_gap_m[e] > 0.0) continue;
    const double Hg = c.net.edge_a[e] == 0 ? clipped : whole;
    EXPECT_NEAR(H[e] / (1.0 / (1.0 / Hg + 2.0 * shell)), 1.0, 1e-9) << e;
  }
}

TEST(GasShare, AViewWithoutSomeWallEdgesKeepsTheSystemsShares) {
  // The conductivity study evaluates a mode on copies of the network holding one wall's edges
  // (its per-wall flows), which must add up to the system's. Particle 1 in a corner: touching
  // particle 0 and two walls, z = 3 (share 2 sqrt(2) R / 3 = 0.943 R < the wall layer's R at
  // cutoff 1.0): a copy with one wall alone must not count z = 2 (no clip) afresh.
  ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {1e-2, 1e-2};
  net.radius_m = {kR, kR};
  net.add_edge(0, 1, 0.0, 0.0, 0.0, true);
  net.add_wall_edge(1, 400.0, 0.0, -1, 0.0, 0.0, true);
  net.add_wall_edge(1, 250.0, 0.0, -1, 0.0, 0.0, true);
  auto sys = make_system(net, {"gas_conduction"}, shared_settings(1.0));
  const std::vector<double> T{300.0, 310.0};
  std::vector<double> q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  // Independent value of one wall's conductance: the sphere-plane integral (S = R - u) to
  // rho_3 = 2 sqrt(2) R / 3, as in the wall test above.
  const double rho3 = 2.0 * std::sqrt(2.0) * kR / 3.0, u_k = kR - kL;
  const double r_k = std::sqrt(kR * kR - u_k * u_k);
  const auto G = [](double r) {
    const double u = std::sqrt(std::max(kR * kR - r * r, 0.0));  // r = R: 0, not a rounding below it
    return -u - kR * std::log(kR - u);
  };
  const double Hw = kPi * r_k * r_k / kL + 2.0 * kPi * (G(r_k) - G(rho3));
  EXPECT_NEAR(boundary / (Hw * (400.0 - 310.0 + 250.0 - 310.0)), 1.0, 1e-9);
  double per_wall = 0.0;
  for (std::size_t keep = 0; keep < 2; ++keep) {
    ThermalNetwork view = sys->network();
    view.clear_wall_edges();
    view.add_wall_edge(1, net.wall_temperature_K[keep], 0.0, -1, 0.0, 0.0, true);
    std::vector<double> qv(2, 0.0);
    double b = 0.0;
    ASSERT_TRUE(sys->modes()[0]->add_heat_flow(view, T, qv, b));
    EXPECT_NEAR(b / (Hw * (net.wall_temperature_K[keep] - 310.0)), 1.0, 1e-9) << keep;
    per_wall += b;
  }
  EXPECT_NEAR(per_wall, boundary, 1e-12 * std::abs(boundary));
}
