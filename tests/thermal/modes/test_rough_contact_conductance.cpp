// The rough-contact law (thermal/modes/RoughContactConductance.h, thermal.conductance =
// "bahrami"): its limits (smooth surfaces give the Hertz constriction 2 k a, no force no
// contact, no gas no micro-gap), the series combination of its three resistances, and its value
// at a worked point (Beaulieu's steel spheres in air) computed here from the papers' formulas,
// with an inverse erfc of its own (bisection) and the micro-contacts' spot integral summed by
// quadrature rather than taken from the closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "thermal/modes/RoughContactConductance.h"

namespace tmdem::thermal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Beaulieu's spheres (issue 39): d 6.4 mm, k 42 W/(m K), E 200 GPa, nu 0.29, sigma 19 nm,
// m 0.056, H_mic 3 GPa; the plate of Lethe's example: k 250, E 100 GPa, nu 0.33, sigma 0.1 nm,
// m 0.056, H_mic 1.8 GPa.
ContactBody steel_sphere() { return {3.2e-3, 42.0, 200e9, 0.29, 19e-9, 0.056, 3e9}; }
ContactBody plate() { return {kInf, 250.0, 100e9, 0.33, 0.1e-9, 0.056, 1.8e9}; }
ContactBody smooth(ContactBody b) {
  b.roughness_m = 0.0;
  b.asperity_slope = 0.0;
  b.microhardness_Pa = 0.0;
  return b;
}
// Air: k_g 0.027 W/(m K), M of accommodation 0.7 on both surfaces, gamma 1.4, Pr 0.69, Lambda 68 nm.
constexpr double kAirK = 0.027;
const double kAirM = 2.0 * (2.0 - 0.7) / 0.7 * (2.0 * 1.4 / 2.4) * 68e-9 / 0.69;
ContactGas air() { return {kAirK, kAirM}; }

// The inverse of erfc by plain bisection (independent of the law's safeguarded Newton).
double erfc_inverse_by_bisection(double y) {
  double lo = -30.0, hi = 30.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid) > y ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The pair's Hertz radius and its peak pressure, written out: 1/R* = 1/R1 + 1/R2,
// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, a = (3 F R* / (4 E*))^(1/3), P0 = 3 F / (2 pi a^2).
struct Spot {
  double a_m, P0_Pa;
};
Spot hertz_spot(const ContactBody& b1, const ContactBody& b2, double F) {
  const double R = 1.0 / (1.0 / b1.radius_m + 1.0 / b2.radius_m);
  const double E = 1.0 / ((1.0 - b1.poisson_ratio * b1.poisson_ratio) / b1.young_modulus_Pa +
                          (1.0 - b2.poisson_ratio * b2.poisson_ratio) / b2.young_modulus_Pa);
  const double a = std::cbrt(3.0 * F * R / (4.0 * E));
  return {a, 3.0 * F / (2.0 * kPi * a * a)};
}

// The micro-contacts of the spot, summed: the Cooper-Mikic-Yovanovich conductance per unit area
// h = 1.25 k (m / sigma) (P / H)^0.95 at the Hertz pressure P(r) = P0 sqrt(1 - r^2/a^2), over
// the disc by the midpoint rule in u = 1 - r^2/a^2 (r dr = -a^2 du / 2), 2e5 points.
double microcontact_conductance_by_quadrature(double k, double sigma, double m, double H,
                                              double a, double P0) {
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    sum += std::pow(P0 * std::sqrt(u) / H, 0.95);
  }
  return 1.25 * k * m / sigma * kPi * a * a * sum / n;  // int_0^a 2 pi r dr f = pi a^2 int_0^1 f du
}

// The three resistances from the papers' formulas (docs/heat-modes.md "Rough contacts").
RoughContactResistances worked_resistances(const ContactBody& b1, const ContactBody& b2, double F,
                                           const ContactGas& gas) {
  const Spot s = hertz_spot(b1, b2, F);
  const double k = 2.0 * b1.conductivity_W_per_mK * b2.conductivity_W_per_mK /
                   (b1.conductivity_W_per_mK + b2.conductivity_W_per_mK);
  const double sigma = std::sqrt(b1.roughness_m * b1.roughness_m + b2.roughness_m * b2.roughness_m);
  const double m = std::sqrt(b1.asperity_slope * b1.asperity_slope + b2.asperity_slope * b2.asperity_slope);
  const double H = std::min(b1.microhardness_Pa, b2.microhardness_Pa);  // the softer surface
  RoughContactResistances r;
  r.macrocontact_K_per_W = 1.0 / (2.0 * k * s.a_m);
  r.microcontacts_K_per_W = 1.0 / microcontact_conductance_by_quadrature(k, sigma, m, H, s.a_m, s.P0_Pa);
  const double a1 = erfc_inverse_by_bisection(2.0 * s.P0_Pa / H);
  const double a2 = erfc_inverse_by_bisection(0.03 * s.P0_Pa / H) - a1;
  r.microgap_K_per_W =
      gas.conductivity_W_per_mK > 0.0
          ? 2.0 * std::sqrt(2.0) * sigma * a2 /
                (kPi * gas.conductivity_W_per_mK * s.a_m * s.a_m *
                 std::log(1.0 + a2 / (a1 + gas.gas_parameter_m / (2.0 * std::sqrt(2.0) * sigma))))
          : kInf;
  return r;
}

TEST(RoughContact, SmoothSurfacesGiveTheHertzConstriction) {
  for (const double F : {1e-3, 0.1, 5.0}) {
    SCOPED_TRACE(F);
    const ContactBody a = smooth(steel_sphere()), b = smooth(steel_sphere()), w = smooth(plate());
    for (const ContactGas& gas : {ContactGas{}, air()}) {
      const double pair = rough_contact_conductance_W_per_K(a, b, F, gas);
      EXPECT_NEAR(pair, hertz_conductance_W_per_K(a, b, F), 1e-14 * pair);
      EXPECT_NEAR(pair, 2.0 * 42.0 * hertz_spot(a, b, F).a_m, 1e-12 * pair);  // H = 2 k a
      const double wall = rough_contact_conductance_W_per_K(a, w, F, gas);
      EXPECT_NEAR(wall, hertz_conductance_W_per_K(a, w, F), 1e-14 * wall);
    }
  }
}

TEST(RoughContact, NoForceNoContact) {
  EXPECT_EQ(rough_contact_conductance_W_per_K(steel_sphere(), steel_sphere(), 0.0, air()), 0.0);
  EXPECT_EQ(rough_contact_conductance_W_per_K(steel_sphere(), plate(), -1.0, air()), 0.0);
  EXPECT_EQ(hertz_peak_pressure_Pa(steel_sphere(), plate(), 0.0), 0.0);
}

// 0.1 N: about the weight of ten spheres, the load a few layers below the plate. The law's
// resistances against the same formulas worked out here, pair and plate, with and without air.
TEST(RoughContact, ResistancesAtAWorkedPointFollowThePapers) {
  const double F = 0.1;
  for (const auto& [b1, b2] : {std::pair{steel_sphere(), steel_sphere()}, {steel_sphere(), plate()}}) {
    for (const ContactGas& gas : {ContactGas{}, air()}) {
      SCOPED_TRACE(std::isinf(b2.radius_m) ? "plate" : "pair");
      SCOPED_TRACE(gas.conductivity_W_per_mK);
      const RoughContactResistances law = rough_contact_resistances(b1, b2, F, gas);
      const RoughContactResistances worked = worked_resistances(b1, b2, F, gas);
      EXPECT_NEAR(law.macrocontact_K_per_W / worked.macrocontact_K_per_W, 1.0, 1e-12);
      EXPECT_NEAR(law.microcontacts_K_per_W / worked.microcontacts_K_per_W, 1.0, 1e-8);
      if (gas.conductivity_W_per_mK > 0.0)
        EXPECT_NEAR(law.microgap_K_per_W / worked.microgap_K_per_W, 1.0, 1e-10);
      else
        EXPECT_TRUE(std::isinf(law.microgap_K_per_W));
      EXPECT_NEAR(hertz_peak_pressure_Pa(b1, b2, F) / hertz_spot(b1, b2, F).P0_Pa, 1.0, 1e-12);
    }
  }
}

// H = 1 / (R_L + 1 / (1/R_s + 1/R_g)): the spot's two paths side by side, in series with the
// constriction; without gas 1 / (R_L + R_s).
TEST(RoughContact, TheResistancesCombineInSeriesAndParallel) {
  const RoughContactResistances r{300.0, 200.0, 600.0};
  EXPECT_NEAR(r.conductance_W_per_K(), 1.0 / (300.0 + 1.0 / (1.0 / 200.0 + 1.0 / 600.0)), 1e-18);
  EXPECT_NEAR((RoughContactResistances{300.0, 200.0, kInf}.conductance_W_per_K()), 1.0 / 500.0, 1e-18);
  EXPECT_NEAR((RoughContactResistances{300.0, 0.0, 600.0}.conductance_W_per_K()), 1.0 / 300.0, 1e-18);
  for (const double F : {0.01, 0.1, 1.0}) {
    const auto vacuum = rough_contact_resistances(steel_sphere(), steel_sphere(), F, {});
    EXPECT_NEAR(rough_contact_conductance_W_per_K(steel_sphere(), steel_sphere(), F, {}),
                1.0 / (vacuum.macrocontact_K_per_W + vacuum.microcontacts_K_per_W), 1e-15);
    const auto gas = rough_contact_resistances(steel_sphere(), steel_sphere(), F, air());
    EXPECT_NEAR(rough_contact_conductance_W_per_K(steel_sphere(), steel_sphere(), F, air()),
                1.0 / (gas.macrocontact_K_per_W +
                       1.0 / (1.0 / gas.microcontacts_K_per_W + 1.0 / gas.microgap_K_per_W)),
                1e-15);
  }
}

TEST(RoughContact, LimitsOfRoughnessLoadAndGas) {
  const ContactBody s = steel_sphere();
  const double F = 0.1, hertz = hertz_conductance_W_per_K(s, s, F);
  // Rougher surfaces conduct less, and below the Hertz spot's 2 k a.
  double previous = hertz;
  for (const double sigma : {1e-9, 19e-9, 0.2e-6, 2e-6}) {
    ContactBody r = s;
    r.roughness_m = sigma;
    const double H = rough_contact_conductance_W_per_K(r, r, F, air());
    EXPECT_LT(H, previous) << sigma;
    previous = H;
  }
  // Under more load the micro-contacts close (R_s ~ a^-2.95 against R_L ~ a^-1): H / (2 k a) -> 1.
  double ratio = 0.0;
  for (const double load : {1e-4, 1e-2, 1.0, 100.0}) {
    const double now = rough_contact_conductance_W_per_K(s, s, load, {}) / hertz_conductance_W_per_K(s, s, load);
    EXPECT_GT(now, ratio) << load;
    EXPECT_LT(now, 1.0) << load;
    ratio = now;
  }
  EXPECT_GT(ratio, 0.99);
  // A thinner gas (larger jump M) conducts less through the micro-gap, down to vacuum.
  const double vacuum = rough_contact_conductance_W_per_K(s, s, F, {});
  double gas_before = kInf;
  for (const double M : {0.0, kAirM, 1e-5, 1e-2}) {
    const double H = rough_contact_conductance_W_per_K(s, s, F, {kAirK, M});
    EXPECT_GT(H, vacuum) << M;
    EXPECT_LT(H, gas_before) << M;
    gas_before = H;
  }
  EXPECT_NEAR(gas_before / vacuum, 1.0, 1e-6);
  // Pressed beyond 2 P0 / H_mic = 1 the spot's mean planes meet: no micro-gap is counted.
  ContactBody soft = s;
  soft.microhardness_Pa = 1.9 * hertz_peak_pressure_Pa(s, s, F);
  EXPECT_TRUE(std::isinf(rough_contact_resistances(soft, soft, F, air()).microgap_K_per_W));
  soft.microhardness_Pa = 2.1 * hertz_peak_pressure_Pa(s, s, F);
  EXPECT_FALSE(std::isinf(rough_contact_resistances(soft, soft, F, air()).microgap_K_per_W));
}

TEST(RoughContact, PairsTakeTheCombinedRoughnessAndTheSofterSurface) {
  // sigma = sqrt(sigma1^2 + sigma2^2), m = sqrt(m1^2 + m2^2): a rough sphere on a smooth one
  // conducts like the rough one against a surface with sigma and m folded in.
  ContactBody rough = steel_sphere(), other = smooth(steel_sphere());
  ContactBody folded = steel_sphere();
  folded.roughness_m = rough.roughness_m / std::sqrt(2.0);
  folded.asperity_slope = rough.asperity_slope / std::sqrt(2.0);
  EXPECT_NEAR(rough_contact_conductance_W_per_K(rough, other, 0.1, air()),
              rough_contact_conductance_W_per_K(folded, folded, 0.1, air()), 1e-15);
  // The softer microhardness counts, whichever side it is on.
  ContactBody hard = steel_sphere();
  hard.microhardness_Pa = 6e9;
  EXPECT_DOUBLE_EQ(rough_contact_conductance_W_per_K(hard, steel_sphere(), 0.1, air()),
                   rough_contact_conductance_W_per_K(steel_sphere(), steel_sphere(), 0.1, air()));
  EXPECT_DOUBLE_EQ(rough_contact_conductance_W_per_K(steel_sphere(), hard, 0.1, air()),
                   rough_contact_conductance_W_per_K(steel_sphere(), steel_sphere(), 0.1, air()));
}

TEST(RoughContact, ARoughSurfaceNeedsSlopeAndMicrohardness) {
  ContactBody no_slope = steel_sphere(), no_hardness = steel_sphere();
  no_slope.asperity_slope = 0.0;
  no_hardness.microhardness_Pa = 0.0;
  EXPECT_THROW(rough_contact_conductance_W_per_K(no_slope, no_slope, 0.1, air()), std::invalid_argument);
  EXPECT_THROW(rough_contact_conductance_W_per_K(no_hardness, no_hardness, 0.1, air()),
               std::invalid_argument);
  // One side's microhardness serves the pair.
  EXPECT_GT(rough_contact_conductance_W_per_K(no_hardness, steel_sphere(), 0.1, air()), 0.0);
}

TEST(RoughContact, InverseErfcInvertsErfc) {
  for (const double y : {1e-300, 1e-12, 3e-4, 0.03, 0.5, 1.0, 1.5, 1.999}) {
    const double x = inverse_erfc(y);
    EXPECT_NEAR(std::erfc(x) / y, 1.0, 1e-12) << y;
    EXPECT_NEAR(x, erfc_inverse_by_bisection(y), 1e-12 * std::max(1.0, std::abs(x))) << y;
  }
  EXPECT_EQ(inverse_erfc(1.0), 0.0);
  EXPECT_THROW(inverse_erfc(0.0), std::invalid_argument);
  EXPECT_THROW(inverse_erfc(2.0), std::invalid_argument);
}

}  // namespace
}  // namespace tmdem::thermal
