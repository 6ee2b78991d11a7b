// The "hertz" normal law (NormalLaw.h, HertzNormalLaw.h, NscdIntegratorHertz.cpp) against
// closed forms: a sphere at rest on the floor sinks Hertz's overlap (m g / K)^(2/3) and carries
// its weight, as the rigid law does (an isostatic packing: both laws agree on the forces); a
// plate pressed onto three spheres of unequal radii, which the rigid law cannot share (any
// split of the load between the two tallest is a solution, the third carries nothing), shares
// the load as Hertz's series springs do, the plate at the height where their forces add up to
// the load; the linearised step law at its tangent point gives Hertz's force; and the scene's
// errors.
#include <gtest/gtest.h>

#include <cmath>

#include "mechanics/HertzScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

TEST(HertzNormalLaw, StepLawAtItsTangentPointIsHertz) {
  // r_n = h F* + k h (delta+ - delta*) with delta+ = -(g~ + h u_n): at rest (u_n = 0) with
  // the overlap delta* (g~ = -delta*), U_n = bias + compliance r_n = 0 gives r_n = h F*.
  const double coefficient = hertz_coefficient(1e11, 1e-3), h = 1e-3;
  for (const double overlap : {1e-9, 1e-7, 1e-5}) {
    const HertzStepLaw law = hertz_step_law(coefficient, overlap, -overlap, h);
    const double r_n = -law.bias_m_per_s / law.compliance_per_kg;
    EXPECT_NEAR(r_n / h, hertz_force(coefficient, overlap), 1e-12 * hertz_force(coefficient, overlap));
    EXPECT_NEAR(hertz_overlap(coefficient, hertz_force(coefficient, overlap)), overlap, 1e-15 * overlap / 1e-9);
  }
  // E* of two bodies, R* of two spheres and of a sphere on a wall.
  EXPECT_DOUBLE_EQ(hertz_effective_modulus(2e11, 0.0, 2e11, 0.0), 1e11);
  EXPECT_DOUBLE_EQ(hertz_effective_radius(2e-3, 2e-3), 1e-3);
  EXPECT_DOUBLE_EQ(hertz_effective_radius(2e-3, 0.0), 2e-3);
}

TEST(HertzNormalLaw, SphereOnTheFloorSinksHertzOverlapAndCarriesItsWeight) {
  const double mass = sphere_mass(kRadius, kDensity), weight = mass * kG;
  const double coefficient = hertz_coefficient(steel_pair_modulus(), kRadius);
  const double overlap = std::cbrt((weight / coefficient) * (weight / coefficient));
  for (const NormalLaw law : {NormalLaw::rigid, NormalLaw::hertz}) {
    ParticleSet set;
    set.add(Vector3d(0, kRadius, 0), kRadius, mass, 0);
    NscdParameters parameters = hertz_parameters();
    parameters.normal_law = law;
    NscdIntegrator sim(std::move(set), {steel(0.5)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                       Vector3d(0, -kG, 0), 3, parameters);
    for (int s = 0; s < 400; ++s) {
      const StepReport report = sim.step();
      ASSERT_TRUE(report.converged) << "step " << s;
    }
    ASSERT_EQ(sim.contacts().size(), 1u);
    const ContactForce& c = sim.contacts()[0];
    EXPECT_NEAR(c.normal_force_N, weight, 1e-9 * weight) << normal_law_name(law);
    if (law == NormalLaw::hertz) {
      EXPECT_NEAR(-c.gap_m, overlap, 1e-6 * overlap);  // 4.7e-8 m for this 1 mm sphere
    } else {
      EXPECT_GE(c.gap_m, -1e-12);
    }
  }
}

TEST(HertzNormalLaw, PlateOnThreeUnequalSpheresSharesTheLoadAsHertzSprings) {
  // Spheres of radii R, R and R - d side by side on the floor y = 0 (no gravity, no friction,
  // far enough apart not to touch), a plate of load L on top. Sphere k is squeezed by the floor
  // and the plate, two contacts in series of the same R* = R_k, each with overlap
  // (2 R_k - y) / 2 for the plate at height y, so it carries F_k = K_k ((2 R_k - y) / 2)^(3/2);
  // the plate rests where sum F_k = L (found here by bisection).
  const double load = 100.0, d = 2e-6;
  const double radius[3] = {kRadius, kRadius, kRadius - d};
  const double modulus = steel_pair_modulus();
  auto force_of = [&](int k, double y) {
    return hertz_force(hertz_coefficient(modulus, radius[k]), (2 * radius[k] - y) / 2);
  };
  double low = 2 * kRadius - 1e-4, high = 2 * kRadius;
  for (int it = 0; it < 200; ++it) {
    const double y = 0.5 * (low + high);
    (force_of(0, y) + force_of(1, y) + force_of(2, y) > load ? low : high) = y;
  }
  const double y = 0.5 * (low + high);
  ASSERT_GT(force_of(2, y), 0.1 * load / 3);  // the small sphere carries a real share

  ParticleSet set;
  for (int k = 0; k < 3; ++k)
    set.add(Vector3d(3 * kRadius * k, radius[k], 0), radius[k], sphere_mass(radius[k], kDensity), 0);
  Wall plate = Wall::through({0, 2 * kRadius, 0}, {0, -1, 0}, 0);
  plate.make_piston(1e-3, load);
  NscdParameters parameters = hertz_parameters();
  NscdIntegrator sim(std::move(set), {steel(0.0)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0), plate},
                     Vector3d::Zero(), 3, parameters);
  for (int s = 0; s < 3000; ++s) {
    const StepReport report = sim.step();
    ASSERT_TRUE(report.converged) << "step " << s << " residual " << report.residual;
  }
  EXPECT_NEAR(sim.walls()[1].point.y(), y, 1e-5 * (2 * kRadius - y));
  double plate_force[3] = {0, 0, 0};
  for (const ContactForce& c : sim.contacts()) {
    if (c.j == wall_code<std::int64_t>(1)) plate_force[c.i] = c.normal_force_N;
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(plate_force[k], force_of(k, y), 1e-6 * load) << "sphere " << k;
  EXPECT_NEAR(plate_force[0] + plate_force[1] + plate_force[2], load, 1e-8 * load);
}

TEST(HertzNormalLaw, NeedsAGaussSeidelSolverAndModuli) {
  ParticleSet set;
  set.add(Vector3d(0, kRadius, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  NscdParameters parameters = hertz_parameters();
  parameters.solver = "apgd";
  try {
    NscdIntegrator sim(set, {steel(0.0)}, {}, Vector3d::Zero(), 3, parameters);
    FAIL() << "apgd accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"nncg\""), std::string::npos) << e.what();
  }
  parameters.solver = "nncg";
  Material soft = steel(0.0);
  soft.young_modulus = 0.0;
  EXPECT_THROW(NscdIntegrator(set, {soft}, {}, Vector3d::Zero(), 3, parameters), std::invalid_argument);
  EXPECT_EQ(parse_normal_law("hertz"), NormalLaw::hertz);
  try {
    parse_normal_law("elastic");
    FAIL() << "elastic accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"rigid\", \"hertz\""), std::string::npos) << e.what();
  }
}
