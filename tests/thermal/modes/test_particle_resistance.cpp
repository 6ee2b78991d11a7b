// The particle's own resistance (thermal/modes/ParticleResistance.h): two spheres and a sphere
// on a wall against closed forms written here from the geometry (cone half-angles by asin, not
// the implementation's form), the series taken on the sum of contact and gas conductance, the
// exact Jacobian and affine reference, and "off" giving today's values bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/GasGapConductance.h"
#include "thermal/modes/ParticleResistance.h"
#include "thermal/steady/SteadyStateSolver.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {


// Shell of a sphere between the core c r and the surface, over the cone of half-angle theta:
// integral of dr / (k Omega r^2) = (1/(c r) - 1/r) / (k Omega), Omega = 2 pi (1 - cos theta).
double cone_shell_K_per_W(double r, double k, double c, double theta) {
  const double omega = 2.0 * std::numbers::pi * (1.0 - std::cos(theta));
  return (1.0 / (c * r) - 1.0 / r) / (k * omega);
}

// Two touching glass-like spheres of different size and conductivity, joined by contact H.
struct TwoSpheres {
  double ra = 1.0e-3, rb = 0.6e-3, ka = 1.0, kb = 3.0, c = 0.5, H = 2.0e-3;
  double Ca = 2.0e-3, Cb = 0.7e-3;
  ThermalNetwork network(bool resistance) const {
    ThermalNetwork net;
    net.resize_nodes(2);
    net.heat_capacity_J_per_K = {Ca, Cb};
    net.radius_m = {ra, rb};
    net.surface_area_m2 = {4 * std::numbers::pi * ra * ra, 4 * std::numbers::pi * rb * rb};
    net.add_edge(0, 1, H, 0.0);
    if (resistance)
      net.shell_resistance_K_sr_per_W = {shell_resistance_K_sr_per_W(ra, ka, c),
                                         shell_resistance_K_sr_per_W(rb, kb, c)};
    return net;
  }
  // a sees b under sin theta_a = r_b / (r_a + r_b), b sees a under sin theta_b = r_a / (r_a + r_b).
  double H_eff() const {
    const double Ra = cone_shell_K_per_W(ra, ka, c, std::asin(rb / (ra + rb)));
    const double Rb = cone_shell_K_per_W(rb, kb, c, std::asin(ra / (ra + rb)));
    return 1.0 / (1.0 / H + Ra + Rb);
  }
};

}  // namespace

TEST(ParticleResistance, ShellAndConeAgainstTheirDefinitions) {
  // S = (1/(c r) - 1/r) / k: r = 1 mm, k = 1, c = 0.5 gives 1000 K sr/W.
  EXPECT_NEAR(shell_resistance_K_sr_per_W(1e-3, 1.0, 0.5), 1000.0, 1e-9);
  // Equal touching spheres: 30 degrees, Omega = 2 pi (1 - sqrt(3)/2).
  EXPECT_NEAR(partner_solid_angle_sr(1.0, 2.0), 2 * std::numbers::pi * (1 - std::sqrt(3.0) / 2), 1e-15);
  // A partner that fills the view (d <= r_b): a hemisphere, never more.
  EXPECT_NEAR(partner_solid_angle_sr(2.0, 1.0), 2 * std::numbers::pi, 1e-15);
  // A far partner: Omega -> pi (r_b/d)^2, no cancellation.
  EXPECT_NEAR(partner_solid_angle_sr(1.0, 1e8), std::numbers::pi * 1e-16, 1e-28);
}

// Steady heat between two held spheres equals H_eff dT; the transient difference of two free
// ones decays as exp(-H_eff (1/C_a + 1/C_b) t) (CVODE, tight tolerances).
TEST(ParticleResistance, TwoSpheresFollowTheSeriesClosedForm) {
  const TwoSpheres p;
  const double H_eff = p.H_eff();
  ASSERT_LT(H_eff, 0.8 * p.H);  // the shells matter here
  auto sys = make_system(p.network(true), {"contact_conduction"});
  ASSERT_EQ(sys->network().edge_series_factor.size(), 1u);
  EXPECT_NEAR(sys->network().edge_series_factor[0] * p.H, H_eff, 1e-14 * H_eff);
  std::vector<double> T{400.0, 300.0}, q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[1], H_eff * 100.0, 1e-12 * H_eff * 100.0);
  EXPECT_EQ(q[0], -q[1]);  // conservative bit for bit

  auto integ = make_thermal_integrator("cvode", *sys, tight_settings("klu", 1e-11));
  integ->initialize(0.0, T, 0.0);
  const double rate = H_eff * (1.0 / p.Ca + 1.0 / p.Cb);
  for (double t : {0.1, 0.5, 1.0, 2.0}) {
    integ->advance_to(t);
    const auto Tt = integ->temperatures_K();
    EXPECT_NEAR(Tt[0] - Tt[1], 100.0 * std::exp(-rate * t), 1e-6) << "t = " << t;
    // Energy: C_a T_a + C_b T_b is kept.
    EXPECT_NEAR(p.Ca * Tt[0] + p.Cb * Tt[1], p.Ca * 400.0 + p.Cb * 300.0, 1e-9);
  }
}

// A held hot sphere, a free middle one and a held cold one: the middle sits where the two
// effective conductances balance (solve_steady_state).
TEST(ParticleResistance, SteadyStateOfAHeldChain) {
  const double r = 1e-3, k = 1.0, c = 0.4, H1 = 1e-3, H2 = 4e-3;
  ThermalNetwork net;
  net.resize_nodes(3);
  net.heat_capacity_J_per_K = {1e-3, 1e-3, 1e-3};
  net.radius_m = {r, r, r};
  net.held = {1, 0, 1};
  net.add_edge(0, 1, H1);
  net.add_edge(1, 2, H2);
  net.shell_resistance_K_sr_per_W.assign(3, shell_resistance_K_sr_per_W(r, k, c));
  auto sys = make_system(net, {"contact_conduction"});
  const double R = cone_shell_K_per_W(r, k, c, std::numbers::pi / 6.0);
  const double G1 = 1.0 / (1.0 / H1 + 2.0 * R), G2 = 1.0 / (1.0 / H2 + 2.0 * R);
  const auto steady = solve_steady_state(*sys, std::vector<double>{350.0, 300.0, 250.0});
  EXPECT_NEAR(steady.T_K[1], (G1 * 350.0 + G2 * 250.0) / (G1 + G2), 1e-9);
}

// A sphere on an isothermal wall: the wall stands for the mirror image, so the shell's cone is
// the one of an equal touching sphere (30 degrees); only the particle's shell is in series.
TEST(ParticleResistance, WallPathHasTheParticleShellOnly) {
  const double r = 1e-3, k = 1.2, c = 0.5, Hw = 3e-3, Tw = 350.0, gap = 0.2e-3;
  ThermalNetwork net;
  net.resize_nodes(1);
  net.heat_capacity_J_per_K = {1e-3};
  net.radius_m = {r};
  net.isothermal_walls = 1;
  net.add_wall_edge(0, Tw, Hw, -1, gap);
  net.shell_resistance_K_sr_per_W = {shell_resistance_K_sr_per_W(r, k, c)};
  auto sys = make_system(net, {"wall_conduction"});
  // The mirror image at 2 (r + gap) from the centre: sin theta = r / (2 (r + gap)).
  const double H_eff = 1.0 / (1.0 / Hw + cone_shell_K_per_W(r, k, c, std::asin(r / (2 * (r + gap)))));
  std::vector<double> T{300.0}, q(1);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[0], H_eff * 50.0, 1e-12 * H_eff * 50.0);
  EXPECT_NEAR(boundary, q[0], 0.0);
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  EXPECT_NEAR(J.diagonal_W_per_K[0], -H_eff, 1e-14 * H_eff);
  // The exact reference of the accuracy study reads the same H'.
  AffineHeatFlow affine(1);
  ASSERT_TRUE(sys->modes()[0]->add_affine_heat_flow(sys->network(), affine));
  ASSERT_EQ(affine.value_W_per_K.size(), 1u);
  EXPECT_NEAR(affine.value_W_per_K[0], -H_eff, 1e-14 * H_eff);
  EXPECT_NEAR(affine.constant_W[0], H_eff * Tw, 1e-12 * H_eff * Tw);
}

namespace {

// Two equal touching spheres (radius r, conductivity k, core c r) joined by contact H, in a gas
// of conductivity kf (surrounding layer), the shells lumped or per ray.
auto touching_pair_in_gas(double r, double k, double c, double H, double kf, bool rays) {
  ThermalNetwork net;
  net.resize_nodes(2);
  net.heat_capacity_J_per_K = {1e-3, 1e-3};
  net.radius_m = {r, r};
  net.add_edge(0, 1, H, 0.0, 0.0, true);
  net.shell_resistance_K_sr_per_W.assign(2, shell_resistance_K_sr_per_W(r, k, c));
  net.gas_shells_per_ray = rays;
  ModeSettings s;
  s.set("gas_conduction", "conductivity", kf);
  s.set("gas_conduction", "model", 1.0);  // choice index 1: surrounding_layer
  return make_system(net, {"contact_conduction", "gas_conduction"}, s);
}

}  // namespace

// Contact and gas share the solid near the contact: the shells are in series with H + H_g, not
// with each separately; each mode carries its part f H, f H_g of that one H'.
TEST(ParticleResistance, SeriesOnTheSumOfContactAndGas) {
  const double r = 1e-3, k = 1.0, c = 0.5, H = 1.5e-3, kf = 0.0262;
  auto sys = touching_pair_in_gas(r, k, c, H, kf, false);
  const double Hg = surrounding_layer_conductance_W_per_K({r, r, 0.0, 0.0}, kf, 0.4, 1.0e-7);
  ASSERT_GT(Hg, 0.1 * H);
  const double R = cone_shell_K_per_W(r, k, c, std::numbers::pi / 6.0);
  const double H_eff = 1.0 / (1.0 / (H + Hg) + 2.0 * R);
  std::vector<double> T{320.0, 300.0}, q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[0], -H_eff * 20.0, 1e-11 * H_eff * 20.0);
  // Per mode: the contact's part is H / (H + H_g) of the whole.
  std::vector<double> qc(2, 0.0);
  ASSERT_TRUE(sys->modes()[0]->add_heat_flow(sys->network(), T, qc, boundary));
  EXPECT_NEAR(qc[0], -H_eff * 20.0 * H / (H + Hg), 1e-11 * H_eff * 20.0);
  // The Jacobian is the constant H' (linear in T).
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  EXPECT_NEAR(J.edge_W_per_K[0], H_eff, 1e-14 * H_eff);
  EXPECT_NEAR(J.diagonal_W_per_K[0], -H_eff, 1e-14 * H_eff);
}

// Off (no shell resistances): no factors, and every flow and Jacobian entry is today's H dT to
// the last bit.
TEST(ParticleResistance, OffGivesTodaysBits) {
  const TwoSpheres p;
  auto sys = make_system(p.network(false), {"contact_conduction"});
  EXPECT_TRUE(sys->network().edge_series_factor.empty());
  const std::vector<double> T{400.0 / 3.0, 300.1};
  std::vector<double> q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  EXPECT_EQ(q[0], p.H * (T[1] - T[0]));
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  EXPECT_EQ(J.edge_W_per_K[0], p.H);
  EXPECT_EQ(J.diagonal_W_per_K[0], -p.H);
}

// With the Hertz law following k(T) the shell is no constant conductance: refused.
TEST(ParticleResistance, RefusedWithConductanceFollowingConductivity) {
  const TwoSpheres p;
  auto net = p.network(true);
  net.conductance_follows_conductivity = true;
  try {
    net.validate();
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("constant conductivities"), std::string::npos) << e.what();
  }
}

namespace {

// The rays' conductance written here by the midpoint rule over the disk, in r itself (the
// implementation integrates in theta, adaptively): k_f sum 2 pi r dr / (max(L_min, S) + l + shells).
double rays_midpoint_W_per_K(double ra, double rb, double gap, double kf, double r_in,
                             double r_out, double min_gap, double jump, double ta, double tb) {
  const int n = 400000;
  const double dr = (r_out - r_in) / n;
  double H = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = r_in + (i + 0.5) * dr;
    const double ca = std::sqrt(1.0 - (r / ra) * (r / ra));
    const double cb = std::isinf(rb) ? 0.0 : std::sqrt(1.0 - (r / rb) * (r / rb));
    const double S = gap + ra * (1.0 - ca) + (std::isinf(rb) ? 0.0 : rb * (1.0 - cb));
    H += 2.0 * std::numbers::pi * r * dr / (std::max(min_gap, S) + jump + ta * ca + tb * cb);
  }
  return kf * H;
}

}  // namespace

// "isothermal_core_rays": each ray of the surrounding layer crosses both shells in series with
// its gas, as a gas thickness k_f S R^2 cos theta (GasGap::shell_gap_a_m). Against the midpoint
// rule for touching spheres of two sizes (r_out = r_min: the layer reaches round the smaller one)
// with a contact disc, and for a sphere on a wall (no shell on the wall's side).
TEST(ParticleResistance, RaysCrossTheShellsInSeriesWithTheGas) {
  const double kf = 0.152, min_gap = 1e-7, jump = 2e-7;
  const double ra = 1e-3, rb = 0.6e-3, ta = 9e-5, tb = 4e-5, a = 2e-5;
  GasGap pair{ra, rb, 0.0, a};
  pair.shell_gap_a_m = ta;
  pair.shell_gap_b_m = tb;
  const double layer = 10.0;  // the whole smaller hemisphere inside the layer
  const double H = surrounding_layer_conductance_W_per_K(pair, kf, layer, min_gap, jump);
  EXPECT_NEAR(H, rays_midpoint_W_per_K(ra, rb, 0.0, kf, a, rb, min_gap, jump, ta, tb), 1e-6 * H);
  // The shells lower the conductance, the more the thicker they are.
  const double without = surrounding_layer_conductance_W_per_K({ra, rb, 0.0, a}, kf, layer, min_gap, jump);
  EXPECT_LT(H, 0.8 * without);
  GasGap wall{ra, std::numeric_limits<double>::infinity(), 1e-5, 0.0};
  wall.shell_gap_a_m = ta;
  wall.shell_gap_b_m = tb;  // a wall has no shell: ignored
  const double r_out = std::sqrt(std::pow(ra + 0.4 * ra, 2) - std::pow(ra + 1e-5, 2));
  const double Hw = surrounding_layer_conductance_W_per_K(wall, kf, 0.4, min_gap, 0.0);
  EXPECT_NEAR(Hw, rays_midpoint_W_per_K(ra, std::numeric_limits<double>::infinity(), 1e-5, kf, 0.0, r_out,
                                        min_gap, 0.0, ta, 0.0), 1e-6 * Hw);
}

// With the shells per ray the gas holds its own shells and stays out of the lumped series:
// the pair carries H / (1 + H (R_a + R_b)) + H_g(rays), H_g with t = k_f S r^2 on each side.
TEST(ParticleResistance, RaysLeaveTheLumpedShellsToTheContactAlone) {
  const double r = 1e-3, k = 1.0, c = 0.65, H = 1.5e-3, kf = 0.0262;
  auto sys = touching_pair_in_gas(r, k, c, H, kf, true);
  GasGap g{r, r, 0.0, 0.0};
  g.shell_gap_a_m = g.shell_gap_b_m = kf * (1.0 / (c * r) - 1.0 / r) / k * r * r;
  const double Hg = surrounding_layer_conductance_W_per_K(g, kf, 0.4, 1.0e-7);
  const double R = cone_shell_K_per_W(r, k, c, std::numbers::pi / 6.0);
  const double H_eff = H / (1.0 + 2.0 * R * H) + Hg;
  std::vector<double> T{320.0, 300.0}, q(2);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  EXPECT_NEAR(q[0], -H_eff * 20.0, 1e-11 * H_eff * 20.0);
  EXPECT_NEAR(q[1], H_eff * 20.0, 1e-11 * H_eff * 20.0);
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  EXPECT_NEAR(J.edge_W_per_K[0], H_eff, 1e-14 * H_eff);
  EXPECT_NEAR(J.diagonal_W_per_K[0], -H_eff, 1e-14 * H_eff);
}

// The gas's shells per ray without shell resistances (a network built by hand): refused.
TEST(ParticleResistance, RaysWithoutShellsAreRefused) {
  auto net = TwoSpheres{}.network(false);
  net.gas_shells_per_ray = true;
  try {
    net.validate();
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shells per ray"), std::string::npos) << e.what();
  }
}
