// Gas in the gaps: the surrounding-layer conductance against closed forms (equal spheres, sphere
// and plane) and against an independent adaptive Simpson quadrature of the model's own integral;
// its limits; the Vargas-McCarthy closed form; the mode's flows and exact Jacobian on a network.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "thermal/ThermalTestSupport.h"
#include "thermal/modes/GasGapConductance.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm,
               double fb, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  if (depth > 60 || std::abs(left + right - whole) <= 15.0 * tol)
    return left + right + (left + right - whole) / 15.0;
  return simpson(f, a, m, fa, flm, fm, left, 0.5 * tol, depth + 1) +
         simpson(f, m, b, fm, frm, fb, right, 0.5 * tol, depth + 1);
}

// The model's defining integral, written out independently of the implementation: the gas
// thickness by plain subtraction, the outer radius from the layer-sphere intersection, and
// adaptive Simpson straight in r (no substitution, no split at the kink).
double layer_integral_by_simpson(const GasGap& g, double layer_fraction, double L_min) {
  const bool plane = std::isinf(g.radius_b_m);
  const double Ra = g.radius_a_m, Rb = g.radius_b_m;
  const double r_min = plane ? Ra : std::min(Ra, Rb), r_max = plane ? Ra : std::max(Ra, Rb);
  const double P = r_max + layer_fraction * r_min;
  double r_out;
  if (plane) {
    const double h = Ra + g.gap_m;
    if (h >= P) return 0.0;
    r_out = std::min(r_min, std::sqrt(P * P - h * h));
  } else {
    const double d = Ra + Rb + g.gap_m;
    if (d >= P + r_min) return 0.0;
    const double x = (d * d + P * P - r_min * r_min) / (2.0 * d);  // from the larger centre
    r_out = x >= 0.0 && d * d > P * P - r_min * r_min ? std::min(r_min, std::sqrt(P * P - x * x)) : r_min;
  }
  const auto S = [&](double r) {
    if (plane) return Ra + g.gap_m - std::sqrt(Ra * Ra - r * r);
    return Ra + Rb + g.gap_m - std::sqrt(std::max(Ra * Ra - r * r, 0.0)) -
           std::sqrt(std::max(Rb * Rb - r * r, 0.0));
  };
  const std::function<double(double)> f = [&](double r) { return 2.0 * kPi * r / std::max(L_min, S(r)); };
  const double a = g.contact_radius_m, b = r_out;
  if (!(b > a)) return 0.0;
  const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
  return simpson(f, a, b, fa, fm, fb, whole, 1e-14, 0);
}

// Closed forms of the same integral (k_f = 1), u = sqrt(R^2 - r^2).
// Equal spheres: S = D - 2u, int 2 pi r dr / S = 2 pi [-u/2 - (D/4) ln(D - 2u)] from u(r_hi) up.
// With a Smoluchowski jump l the integrand is 1 / (max(L, S) + l): D + l in place of D in the
// logarithm's part, L + l in the constant part (r_k still where S = L).
double equal_spheres_closed_form(double R, double gap, double a, double layer_fraction, double L,
                                 double l = 0.0) {
  const double D = 2.0 * R + gap, P = R * (1.0 + layer_fraction);
  double r_out = R;
  if (D * D > P * P - R * R) {
    const double x = (D * D + P * P - R * R) / (2.0 * D);
    r_out = std::min(R, std::sqrt(P * P - x * x));
  }
  const double u_k = 0.5 * (D - L);  // S = L there
  const double r_k = u_k < R ? std::clamp(std::sqrt(R * R - u_k * u_k), a, r_out) : a;
  const auto F = [&](double r) {
    const double u = std::sqrt(R * R - r * r);
    return -0.5 * u - 0.25 * (D + l) * std::log(D + l - 2.0 * u);
  };
  return kPi * (r_k * r_k - a * a) / (L + l) + 2.0 * kPi * (F(r_k) - F(r_out));
}

// Sphere and plane: S = h - u, int 2 pi r dr / S = 2 pi [-u - h ln(h - u)] from u(r_hi) up.
double sphere_plane_closed_form(double R, double gap, double a, double layer_fraction, double L,
                                double l = 0.0) {
  const double h = R + gap, P = R * (1.0 + layer_fraction);
  const double r_out = std::min(R, std::sqrt(P * P - h * h));
  const double u_k = h - L;
  const double r_k = u_k < R ? std::clamp(std::sqrt(R * R - u_k * u_k), a, r_out) : a;
  const auto G = [&](double r) {
    const double u = std::sqrt(R * R - r * r);
    return -u - (h + l) * std::log(h + l - u);
  };
  return kPi * (r_k * r_k - a * a) / (L + l) + 2.0 * kPi * (G(r_k) - G(r_out));
}

GasGap spheres(double Ra, double Rb, double gap, double a = 0.0) { return {Ra, Rb, gap, a}; }
GasGap plane(double R, double gap, double a = 0.0) { return {R, kInf, gap, a}; }

constexpr double kR = 1e-3, kLayer = 0.4, kL = 1e-7;

}  // namespace

TEST(GasGap, SurroundingLayerEqualSpheresMatchesClosedForm) {
  for (const auto& [gap, a] : {std::pair{0.0, 0.0}, {0.0, 2e-5}, {-2e-9, 0.0}, {5e-8, 0.0},
                               {1e-5, 0.0}, {0.1 * kR, 0.0}, {0.3 * kR, 0.0}}) {
    const double H = surrounding_layer_conductance_W_per_K(spheres(kR, kR, gap, a), 1.0, kLayer, kL);
    const double exact = equal_spheres_closed_form(kR, gap, a, kLayer, kL);
    EXPECT_NEAR(H / exact, 1.0, 1e-9) << "gap " << gap << " a " << a;
  }
}

TEST(GasGap, SurroundingLayerSpherePlaneMatchesClosedForm) {
  for (const auto& [gap, a] : {std::pair{0.0, 0.0}, {0.0, 3e-5}, {1e-6, 0.0}, {0.2 * kR, 0.0}}) {
    const double H = surrounding_layer_conductance_W_per_K(plane(kR, gap, a), 1.0, kLayer, kL);
    const double exact = sphere_plane_closed_form(kR, gap, a, kLayer, kL);
    EXPECT_NEAR(H / exact, 1.0, 1e-9) << "gap " << gap << " a " << a;
  }
}

// A rarefied gas: the Smoluchowski jump l widens every gap by l. Jump lengths from far below the
// smallest gas thickness (1 bar of air is l = 1.7e-7 m) to far above the particle (near vacuum).
TEST(GasGap, RarefiedSurroundingLayerMatchesClosedForm) {
  for (const double l : {1e-9, 1.66e-7, 1e-5, 1e-3}) {
    for (const auto& [gap, a] : {std::pair{0.0, 0.0}, {0.0, 2e-5}, {5e-8, 0.0}, {0.1 * kR, 0.0}}) {
      const double H = surrounding_layer_conductance_W_per_K(spheres(kR, kR, gap, a), 1.0, kLayer, kL, l);
      EXPECT_NEAR(H / equal_spheres_closed_form(kR, gap, a, kLayer, kL, l), 1.0, 1e-9)
          << "spheres, l " << l << " gap " << gap << " a " << a;
      const double Hp = surrounding_layer_conductance_W_per_K(plane(kR, gap, a), 1.0, kLayer, kL, l);
      EXPECT_NEAR(Hp / sphere_plane_closed_form(kR, gap, a, kLayer, kL, l), 1.0, 1e-9)
          << "plane, l " << l << " gap " << gap << " a " << a;
    }
  }
}

// The jump length as the VDI Heat Atlas writes it (l = 2 (2 - gamma) / gamma Lambda, Lambda
// proportional to 1 / p), and the pressure trend it gives: H rises with the pressure towards the
// continuum value, and at low pressure (l far above every gap) falls as the free-molecule limit
// k_f pi (r_out^2 - a^2) / l, i.e. in proportion to p.
TEST(GasGap, PressureTrendFromContinuumToFreeMolecules) {
  EXPECT_EQ(gas_jump_length_m(0.0, 6.8e-8, 0.9), 0.0);  // continuum
  EXPECT_NEAR(gas_jump_length_m(101325.0, 6.8e-8, 0.9), 2.0 * 1.1 / 0.9 * 6.8e-8, 1e-22);
  EXPECT_NEAR(gas_jump_length_m(1013.25, 6.8e-8, 1.0), 2.0 * 6.8e-6, 1e-20);
  const GasGap touching = spheres(kR, kR, 0.0);
  const double continuum = surrounding_layer_conductance_W_per_K(touching, 0.026, kLayer, kL);
  double previous = 0.0;
  for (const double p : {1e-2, 1.0, 1e2, 1e4, 1e5, 1e7, 1e9}) {
    const double H = surrounding_layer_conductance_W_per_K(touching, 0.026, kLayer, kL,
                                                           gas_jump_length_m(p, 6.8e-8, 0.9));
    EXPECT_GT(H, previous) << p << " Pa";
    EXPECT_LT(H, continuum) << p << " Pa";
    previous = H;
  }
  EXPECT_NEAR(previous / continuum, 1.0, 1e-3);  // 1e9 Pa: l = 1.7e-11 m
  // Free molecules: r_out of equal spheres in a layer of 0.4 R (the layer sphere meets the
  // other sphere at x = D/2 + (P^2 - R^2)/(2D)).
  const double P = kR * (1.0 + kLayer), x = kR + (P * P - kR * kR) / (4.0 * kR);
  const double r_out = std::sqrt(P * P - x * x);
  const double l = gas_jump_length_m(1e-3, 6.8e-8, 0.9);  // 17 m
  const double H = surrounding_layer_conductance_W_per_K(touching, 0.026, kLayer, kL, l);
  EXPECT_NEAR(H / (0.026 * kPi * r_out * r_out / l), 1.0, 1e-4);
}

TEST(GasGap, SurroundingLayerMatchesQuadratureOfItsIntegral) {
  // Unequal radii have no closed form: against adaptive Simpson, 1e-6 relative.
  for (const GasGap& g : {spheres(kR, 0.6 * kR, 0.0), spheres(0.6 * kR, kR, 0.0, 1e-5),
                          spheres(kR, 0.5 * kR, 0.05 * kR), spheres(kR, 0.8 * kR, 0.25 * kR),
                          spheres(kR, kR, 0.0), plane(0.7 * kR, 0.1 * kR)}) {
    const double H = surrounding_layer_conductance_W_per_K(g, 0.026, kLayer, kL);
    const double Q = 0.026 * layer_integral_by_simpson(g, kLayer, kL);
    ASSERT_GT(Q, 0.0);
    EXPECT_NEAR(H / Q, 1.0, 1e-6) << g.radius_a_m << " " << g.radius_b_m << " gap " << g.gap_m;
  }
}

TEST(GasGap, SurroundingLayerLimits) {
  const auto H = [](const GasGap& g) { return surrounding_layer_conductance_W_per_K(g, 1.0, kLayer, kL); };
  // Beyond the layer (the cutoff) nothing conducts, and the conductance falls to 0 continuously.
  EXPECT_EQ(H(spheres(kR, kR, kLayer * kR)), 0.0);
  EXPECT_EQ(H(spheres(kR, kR, 2.0 * kLayer * kR)), 0.0);
  EXPECT_EQ(H(plane(kR, kLayer * kR)), 0.0);
  EXPECT_LT(H(spheres(kR, kR, kLayer * kR * (1.0 - 1e-6))), 1e-6 * H(spheres(kR, kR, 0.0)));
  // Closer is better, all the way to touching.
  double previous = 0.0;
  for (double gap : {0.3, 0.1, 0.01, 1e-3, 1e-4, 0.0}) {
    const double now = H(spheres(kR, kR, gap * kR));
    EXPECT_GT(now, previous) << gap;
    previous = now;
  }
  // Touching: the lens is capped at L_min, so the conductance is finite and grows like
  // pi R ln(R / L_min) as L_min falls (flux-tube limit).
  const double h1 = surrounding_layer_conductance_W_per_K(spheres(kR, kR, 0.0), 1.0, kLayer, 1e-8);
  const double h2 = surrounding_layer_conductance_W_per_K(spheres(kR, kR, 0.0), 1.0, kLayer, 1e-9);
  EXPECT_NEAR((h2 - h1) / (kPi * kR * std::log(10.0)), 1.0, 1e-3);
  // A gas layer thinner than L_min everywhere conducts as one slab of thickness L_min.
  const double slab = surrounding_layer_conductance_W_per_K(spheres(kR, kR, 0.0), 1.0, kLayer, 10.0 * kR);
  const double P = (1.0 + kLayer) * kR, x = (4.0 * kR * kR + P * P - kR * kR) / (4.0 * kR);
  EXPECT_NEAR(slab, kPi * (P * P - x * x) / (10.0 * kR), 1e-12 * slab);
}

TEST(GasGap, VargasMcCarthyClosedFormAndLimits) {
  const double k = 0.026;
  EXPECT_NEAR(vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0), k),
              2.0 * kPi * k * kR / (1.0 - kPi / 4.0), 1e-15);
  // Mean radius of unequal spheres; a plane counts with the particle's radius.
  EXPECT_DOUBLE_EQ(vargas_mccarthy_conductance_W_per_K(spheres(kR, 0.5 * kR, 0.0), k),
                   vargas_mccarthy_conductance_W_per_K(spheres(0.75 * kR, 0.75 * kR, 0.0), k));
  EXPECT_DOUBLE_EQ(vargas_mccarthy_conductance_W_per_K(plane(kR, 0.0), k),
                   vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0), k));
  // a = R/2: (R - a)(1 - a^2 / 2R^2) = R/2 * 7/8.
  EXPECT_NEAR(vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0, 0.5 * kR), k),
              2.0 * kPi * k * kR * 7.0 / 16.0 / (1.0 - kPi / 4.0), 1e-15);
  EXPECT_EQ(vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0, kR), k), 0.0);
}

namespace {

// Three particles: 0-1 touching, 1-2 a near pair at 0.1 R, 0-2 beyond the cutoff; particle 0
// also near an isothermal wall at 400 K.
ThermalNetwork gas_network() {
  ThermalNetwork net;
  net.resize_nodes(3);
  net.heat_capacity_J_per_K = {1e-2, 2e-2, 1.5e-2};
  net.radius_m = {kR, kR, 0.8 * kR};
  net.add_edge(0, 1, 0.0, 0.0, 1e-5, true);
  net.add_edge(1, 2, 0.0, 0.1 * kR, 0.0, false);
  net.add_edge(0, 2, 0.0, 0.9 * kR, 0.0, false);
  net.add_wall_edge(0, 400.0, 0.0, -1, 0.05 * kR, 0.0, false);
  return net;
}

ModeSettings gas_settings(double model) {
  ModeSettings s;
  s.set("gas_conduction", "model", model);
  s.set("gas_conduction", "conductivity", 0.05);
  return s;
}

}  // namespace

TEST(GasConductionMode, FlowsAreTheLawsConductancesAndTheJacobianIsExact) {
  const auto net = gas_network();
  auto sys = make_system(net, {"gas_conduction"}, gas_settings(1.0));  // surrounding_layer
  const std::vector<double> T{300.0, 350.0, 330.0};
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(T, q, boundary));
  const double H01 = surrounding_layer_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05, kLayer, kL);
  const double H12 = surrounding_layer_conductance_W_per_K(spheres(kR, 0.8 * kR, 0.1 * kR), 0.05, kLayer, kL);
  const double Hw = surrounding_layer_conductance_W_per_K(plane(kR, 0.05 * kR), 0.05, kLayer, kL);
  EXPECT_GT(H12, 0.0);
  EXPECT_DOUBLE_EQ(q[0], H01 * (350.0 - 300.0) + Hw * (400.0 - 300.0));  // nothing from 2
  EXPECT_DOUBLE_EQ(q[2], H12 * (350.0 - 330.0));
  EXPECT_NEAR(q[0] + q[1] + q[2], Hw * 100.0, 1e-15);  // pairs conserve; only the wall adds
  EXPECT_DOUBLE_EQ(boundary, Hw * 100.0);
  // Jacobian against central differences (the flows are linear: exact to round-off).
  JacobianEvaluation J;
  sys->evaluate_jacobian(T, J);
  std::vector<double> values(sys->pattern().nonzeros());
  sys->jacobian_values(J, values);
  for (int j = 0; j < 3; ++j) {
    auto Tp = T, Tm = T;
    Tp[j] += 1.0;
    Tm[j] -= 1.0;
    std::vector<double> qp(3), qm(3);
    ASSERT_TRUE(sys->time_derivative(Tp, qp, boundary));
    ASSERT_TRUE(sys->time_derivative(Tm, qm, boundary));
    const auto& P = sys->pattern();
    for (int i = 0; i < 3; ++i) {
      double Jij = 0.0;
      for (auto s = P.column_start[j]; s < P.column_start[j + 1]; ++s)
        if (P.row_index[s] == i) Jij = values[s];
      EXPECT_NEAR(Jij, 0.5 * (qp[i] - qm[i]), 1e-12) << i << "," << j;
    }
  }
}

TEST(GasConductionMode, VargasMcCarthyCountsTouchingPairsOnly) {
  auto sys = make_system(gas_network(), {"gas_conduction"}, gas_settings(0.0));
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(std::vector<double>{300.0, 350.0, 330.0}, q, boundary));
  const double H01 = vargas_mccarthy_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05);
  EXPECT_DOUBLE_EQ(q[0], H01 * 50.0);
  EXPECT_EQ(q[2], 0.0);
  EXPECT_EQ(boundary, 0.0);
}

TEST(GasConductionMode, AModelIndexOutsideTheChoicesIsRefused) {
  // The scene maps names to indices (an unknown name is refused there, listing the valid ones:
  // test_scene_gas); a bad index set directly is refused naming the key.
  ModeSettings s;
  s.set("gas_conduction", "model", 2.0);
  try {
    make_heat_transfer_mode("gas_conduction", s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gas_conduction.model"), std::string::npos) << e.what();
  }
}
