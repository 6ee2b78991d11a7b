// Gas in the gaps: the surrounding-layer conductance against closed forms (equal spheres, sphere
// and plane) and against an independent adaptive Simpson quadrature of the model's own integral;
// its limits; the Vargas-McCarthy closed form; Bahrami's gas parameter and macro-gap conductance.
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

namespace {

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

