// The Hertz contact law with a flattened spot (thermal/modes/ConductanceLaw.h): a = max(a_Hertz,
// f R*), checked against the Hertz closed form on both sides of the force where the two meet,
// F_c = 4 E* (f R*)^3 / (3 R*), for a pair of spheres and a sphere on a wall (R* = r).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "thermal/modes/ConductanceLaw.h"

namespace tmdem::thermal {
namespace {

constexpr double kLawSteelE = 2.1e11, kLawSteelNu = 0.3, kLawSteelK = 50.0;

ContactBody steel_sphere(double radius_m) { return {radius_m, kLawSteelK, kLawSteelE, kLawSteelNu}; }
ContactBody steel_wall() { return {std::numeric_limits<double>::infinity(), kLawSteelK, kLawSteelE, kLawSteelNu}; }

double effective_modulus_Pa() { return 1.0 / (2.0 * (1.0 - kLawSteelNu * kLawSteelNu) / kLawSteelE); }

TEST(FlattenedContact, SpotIsTheLargerOfHertzAndTheFlattenedRadius) {
  const double f = 0.025;
  struct Case {
    ContactBody a, b;
    double R_star_m;
  };
  // Equal spheres of 1 mm (R* = 0.5 mm), a 1 mm and a 3 mm sphere (R* = 0.75 mm), a wall (R* = r).
  for (const Case& c : {Case{steel_sphere(1e-3), steel_sphere(1e-3), 0.5e-3},
                        Case{steel_sphere(1e-3), steel_sphere(3e-3), 0.75e-3},
                        Case{steel_sphere(1e-3), steel_wall(), 1e-3}}) {
    SCOPED_TRACE(c.R_star_m);
    const double E = effective_modulus_Pa();
    const double spot_m = f * c.R_star_m;
    const double F_c = 4.0 * E * spot_m * spot_m * spot_m / (3.0 * c.R_star_m);  // a_Hertz = f R*
    EXPECT_NEAR(hertz_contact_radius_m(c.a, c.b, F_c), spot_m, 1e-12 * spot_m);
    for (const double F : {1e-3 * F_c, 0.5 * F_c, 2.0 * F_c, 30.0 * F_c}) {
      SCOPED_TRACE(F);
      const double hertz_m = std::cbrt(3.0 * F * c.R_star_m / (4.0 * E));
      const double expected_m = std::max(hertz_m, spot_m);
      EXPECT_NEAR(hertz_contact_radius_m(c.a, c.b, F, f), expected_m, 1e-12 * expected_m);
      EXPECT_NEAR(hertz_contact_radius_m(c.a, c.b, F), hertz_m, 1e-12 * hertz_m);  // f = 0: Hertz
      // H = 2 k a with the harmonic mean of equal conductivities: k.
      EXPECT_NEAR(hertz_conductance_W_per_K(c.a, c.b, F, f), 2.0 * kLawSteelK * expected_m,
                  1e-12 * kLawSteelK * expected_m);
    }
    // No force, no contact: no spot, flattened or not.
    EXPECT_EQ(hertz_contact_radius_m(c.a, c.b, 0.0, f), 0.0);
    EXPECT_EQ(hertz_conductance_W_per_K(c.a, c.b, -1.0, f), 0.0);
  }
}

}  // namespace
}  // namespace tmdem::thermal
