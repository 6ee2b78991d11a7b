// Gas in the gaps: the surrounding-layer conductance against closed forms (equal spheres, sphere
// and plane) and against an independent adaptive Simpson quadrature of the model's own integral;
// its limits; the Vargas-McCarthy closed form; the mode's flows and exact Jacobian on a network.
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
#include "thermal/modes/ParticleResistance.h"

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

// Bahrami's gas parameter, M = ((2 - a1)/a1 + (2 - a2)/a2) (2 g / (1 + g)) Lambda / Pr, with the
// mean free path inversely proportional to the pressure.
TEST(GasGap, BahramiGasParameter) {
  const double M = gas_parameter_m(101325.0, 68e-9, 0.7, 0.7, 1.4, 0.69);
  EXPECT_NEAR(M / (2.0 * 1.3 / 0.7 * (2.8 / 2.4) * 68e-9 / 0.69), 1.0, 1e-14);
  EXPECT_NEAR(gas_parameter_m(1013.25, 68e-9, 0.7, 0.7, 1.4, 0.69) / M, 100.0, 1e-12);
  EXPECT_NEAR(gas_parameter_m(101325.0, 68e-9, 1.0, 0.5, 1.0, 1.0), (1.0 + 3.0) * 68e-9, 1e-22);
  EXPECT_EQ(gas_parameter_m(0.0, 68e-9, 0.7, 0.7, 1.4, 0.69), 0.0);  // continuum
}

namespace {

// Closed forms of the macro-gap (k_f = 1): the gas from the rim of the contact disc (radius a),
// where the surfaces meet, out to the sphere's radius, in series with the jump M.
// Equal spheres, u = sqrt(R^2 - r^2): delta = 2 (u_a - u), int_0^u_a 2 pi u du / (S - 2u),
// S = 2 u_a + M: (pi / 2) [S ln(S / (S - A)) - A], A = 2 u_a (Bahrami et al. 2006, B = 0).
double macrogap_equal_spheres(double R, double a, double M) {
  const double A = 2.0 * std::sqrt(R * R - a * a), S = A + M;
  return 0.5 * kPi * (S * std::log(S / M) - A);  // S - A = M
}
// Sphere and plane: delta = u_a - u, int_0^u_a 2 pi u du / (S - u), S = u_a + M.
double macrogap_sphere_plane(double R, double a, double M) {
  const double u = std::sqrt(R * R - a * a), S = u + M;
  return 2.0 * kPi * (S * std::log(S / M) - u);  // S - u = M
}
// The defining integral by adaptive Simpson straight in r (plain subtraction for the opening).
double macrogap_by_simpson(const GasGap& g, double M) {
  const bool plane = std::isinf(g.radius_b_m);
  const double Ra = g.radius_a_m, Rb = g.radius_b_m, a = g.contact_radius_m;
  const double r_min = plane ? Ra : std::min(Ra, Rb);
  const auto sag = [](double R, double r) { return std::isinf(R) ? 0.0 : R - std::sqrt(R * R - r * r); };
  const std::function<double(double)> f = [&](double r) {
    return 2.0 * kPi * r / (sag(Ra, r) + sag(Rb, r) - sag(Ra, a) - sag(Rb, a) + M);
  };
  const double fa = f(a), fm = f(0.5 * (a + r_min)), fb = f(r_min);
  const double whole = (r_min - a) / 6.0 * (fa + 4.0 * fm + fb);
  return simpson(f, a, r_min, fa, fm, fb, whole, 1e-11 * whole, 0);
}

}  // namespace

// From air at 1 atm (M 0.37 um for Beaulieu's spheres) to a gas far thinner than the sphere.
TEST(GasGap, BahramiMacrogapMatchesItsClosedForms) {
  const double R = 3.2e-3;
  for (const double M : {3.7e-7, 1e-8, 1e-5, 1e-2}) {
    for (const double a : {0.0, 1e-5, 1e-4, 0.5 * R}) {
      SCOPED_TRACE(M);
      SCOPED_TRACE(a);
      EXPECT_NEAR(bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0, a), 1.0, M) /
                      macrogap_equal_spheres(R, a, M), 1.0, 1e-10);
      EXPECT_NEAR(bahrami_macrogap_conductance_W_per_K(plane(R, 0.0, a), 1.0, M) /
                      macrogap_sphere_plane(R, a, M), 1.0, 1e-10);
    }
  }
  // Linear in k_f; the overlap or gap of the packing plays no part (the surfaces meet at a).
  const double once = bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0, 1e-5), 1.0, 3.7e-7);
  EXPECT_NEAR(bahrami_macrogap_conductance_W_per_K(spheres(R, R, -1e-6, 1e-5), 0.027, 3.7e-7),
              0.027 * once, 1e-13 * once);
}

TEST(GasGap, BahramiMacrogapOfUnequalSpheresMatchesQuadrature) {
  const double R = 3.2e-3, M = 3.7e-7;
  for (const GasGap& g : {spheres(R, 0.5 * R, 0.0), spheres(0.5 * R, R, 0.0, 2e-5),
                          spheres(R, 0.9 * R, 0.0, 1e-4), plane(0.7 * R, 0.0, 3e-5)}) {
    const double H = bahrami_macrogap_conductance_W_per_K(g, 1.0, M);
    EXPECT_NEAR(H / macrogap_by_simpson(g, M), 1.0, 1e-7) << g.radius_a_m << " " << g.radius_b_m;
  }
}

TEST(GasGap, BahramiMacrogapLimits) {
  const double R = 3.2e-3;
  // A thinner gas conducts less; in the free-molecule limit (M far above the sphere) the gap
  // conducts as a slab of thickness M over the disc from a to R: pi (R^2 - a^2) / M.
  double previous = kInf;
  for (const double M : {1e-9, 3.7e-7, 1e-4, 1e-1}) {
    const double H = bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0), 1.0, M);
    EXPECT_LT(H, previous) << M;
    previous = H;
  }
  EXPECT_NEAR(bahrami_macrogap_conductance_W_per_K(plane(R, 0.0, 1e-4), 1.0, 1e3) /
                  (kPi * (R * R - 1e-8) / 1e3), 1.0, 1e-5);
  // A continuum gas would conduct infinitely at the rim: for equal spheres H grows like
  // pi R ln(1/M), the logarithm the paper's M closes.
  const double h1 = bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0), 1.0, 1e-8);
  const double h2 = bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0), 1.0, 1e-9);
  EXPECT_NEAR((h2 - h1) / (kPi * R * std::log(10.0)), 1.0, 1e-4);
  // A larger contact disc leaves less gas; a disc as large as the sphere leaves none.
  EXPECT_LT(bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0, 1e-4), 1.0, 3.7e-7),
            bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0, 1e-5), 1.0, 3.7e-7));
  EXPECT_EQ(bahrami_macrogap_conductance_W_per_K(spheres(R, R, 0.0, R), 1.0, 3.7e-7), 0.0);
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

// Building the gas mode with `s` throws std::invalid_argument naming `key`.
void expect_gas_mode_refused(const ModeSettings& s, const std::string& key) {
  try {
    make_heat_transfer_mode("gas_conduction", s);
    ADD_FAILURE() << "built without error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
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

// fluid.model = "bahrami": the macro-gap of touching pairs (and touching isothermal walls) with
// the gas parameter M of the section's pressure, mean free path, accommodation, gamma and Pr;
// near pairs get nothing, and without a pressure the model is refused naming the key.
TEST(GasConductionMode, BahramiCountsTouchingPairsWithTheSectionsGasParameter) {
  ThermalNetwork net = gas_network();
  net.add_wall_edge(2, 400.0, 0.0, -1, 0.0, 2e-6, true);  // 2 rests on a wall at 400 K
  ModeSettings s = gas_settings(2.0);
  s.set("gas_conduction", "pressure", 101325.0);
  s.set("gas_conduction", "accommodation", 0.7);
  s.set("gas_conduction", "heat_capacity_ratio", 1.4);
  s.set("gas_conduction", "prandtl", 0.69);
  auto sys = make_system(net, {"gas_conduction"}, s);
  std::vector<double> q(3);
  double boundary = 0.0;
  ASSERT_TRUE(sys->heat_flow(std::vector<double>{300.0, 350.0, 330.0}, q, boundary));
  const double M = 2.0 * 1.3 / 0.7 * (2.8 / 2.4) * 6.8e-8 / 0.69;  // mean_free_path's default
  const double H01 = bahrami_macrogap_conductance_W_per_K(spheres(kR, kR, 0.0, 1e-5), 0.05, M);
  const double Hw = bahrami_macrogap_conductance_W_per_K(plane(0.8 * kR, 0.0, 2e-6), 0.05, M);
  EXPECT_NEAR(q[0], H01 * 50.0, 1e-12 * H01 * 50.0);  // not the near wall at 0.05 R
  EXPECT_NEAR(q[2], Hw * 70.0, 1e-12 * Hw * 70.0);    // not the near pair 1-2
  EXPECT_NEAR(boundary, Hw * 70.0, 1e-12 * Hw * 70.0);
  s.set("gas_conduction", "pressure", 0.0);
  expect_gas_mode_refused(s, "gas_conduction.pressure");
}

TEST(GasConductionMode, AModelIndexOutsideTheChoicesIsRefused) {
  // The scene maps names to indices (an unknown name is refused there, listing the valid ones:
  // test_scene_gas); a bad index set directly is refused naming the key.
  ModeSettings s;
  s.set("gas_conduction", "model", 3.0);
  expect_gas_mode_refused(s, "gas_conduction.model");
}

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
