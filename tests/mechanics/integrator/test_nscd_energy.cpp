// The energy account of a Moreau-Jean step (NscdIntegrator.h): kinetic + potential change plus
// contact dissipation plus the theta scheme's numerical damping is zero to round-off, and the
// contact dissipation is the exact slip work / impact loss of textbook cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechanics/MechanicsTestScenes.h"

using namespace tmdem::mechanics;
using namespace tmdem::mechanics::test;
using Eigen::Vector3d;

namespace {

// A plane through the origin tilted by alpha about z: normal (-sin a, cos a, 0), downhill
// direction (-cos a, -sin a, 0).
Wall incline(double alpha) {
  return Wall::through({0, 0, 0}, {-std::sin(alpha), std::cos(alpha), 0}, 0);
}

// One sphere resting (touching, at rest) on the incline at the origin's foot point.
NscdIntegrator sphere_on_incline(double alpha, double friction, bool spin,
                                 NscdParameters parameters = nlgs_parameters()) {
  ParticleSet set;
  const Vector3d n(-std::sin(alpha), std::cos(alpha), 0);
  set.add(kRadius * n, kRadius, sphere_mass(kRadius, kDensity), 0);
  // No rotation: an inertia so large that no torque of the run spins the sphere measurably
  // (1/I = 1e-30 of a sphere's), i.e. a block sliding on its contact point.
  if (!spin) set.inertia[0] *= 1e30;
  return NscdIntegrator(std::move(set), {steel(friction)}, {incline(alpha)}, Vector3d(0, -kG, 0),
                        3, parameters);
}

struct Account {
  double energy_change = 0.0, contact = 0.0, numerical = 0.0, contact_listed = 0.0;
};

Account run(NscdIntegrator& sim, int steps) {
  Account a;
  for (int s = 0; s < steps; ++s) {
    const StepReport r = sim.step();
    a.energy_change += r.energy_change_J;
    a.contact += r.contact_dissipation_J;
    a.numerical += r.numerical_dissipation_J;
    for (const auto& c : sim.contacts()) a.contact_listed += c.dissipated_power_W * sim.parameters().time_step;
  }
  return a;
}

}  // namespace

// A block (no rotation) sliding down a 40 degree incline with mu = 0.3: the friction impulse is
// mu N h every step and the contact dissipation is mu m g cos(a) times the distance slid.
TEST(NscdEnergy, SlidingBlockDissipatesMuNTimesDistance) {
  const double alpha = 40.0 * std::numbers::pi / 180.0, mu = 0.3;
  for (double theta : {0.5, 0.7, 1.0}) {
    NscdParameters p = nlgs_parameters();
    p.theta = theta;
    p.tolerance = 1e-12;
    auto sim = sphere_on_incline(alpha, mu, false, p);
    const Vector3d x0 = sim.particles().position[0];
    const Account a = run(sim, 400);
    const double m = sim.particles().mass[0];
    const double distance = (sim.particles().position[0] - x0).norm();
    const double expected = mu * m * kG * std::cos(alpha) * distance;
    EXPECT_NEAR(a.contact, expected, 1e-9 * expected) << "theta " << theta;
    EXPECT_NEAR(a.contact_listed, a.contact, 1e-12 * expected) << "theta " << theta;
    // It slid: a = g (sin a - mu cos a), about 0.5 * a * t^2.
    const double t = 400 * p.time_step;
    EXPECT_NEAR(distance, 0.5 * kG * (std::sin(alpha) - mu * std::cos(alpha)) * t * t,
                0.02 * distance);
    // The identity closes for every theta; the scheme's own damping is 0 only at theta = 1/2.
    const double scale = std::abs(a.energy_change);
    EXPECT_NEAR(a.energy_change + a.contact + a.numerical, 0.0, 1e-12 * scale) << "theta " << theta;
    if (theta == 0.5) {
      EXPECT_EQ(a.numerical, 0.0);
    } else {
      EXPECT_GT(a.numerical, 0.0);
    }
  }
}

// A sphere on a 20 degree incline with mu = 0.3 rolls without slipping (tan a < 7/2 mu): the
// contact point does not slide, so nothing is dissipated.
TEST(NscdEnergy, RollingWithoutSlipDissipatesNothing) {
  const double alpha = 20.0 * std::numbers::pi / 180.0;
  NscdParameters p = nlgs_parameters();
  p.tolerance = 1e-12;
  auto sim = sphere_on_incline(alpha, 0.3, true, p);
  const Account a = run(sim, 400);
  // Potential energy became kinetic energy; nothing was lost.
  const double scale = sim.kinetic_energy();
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(std::abs(a.contact), 1e-12 * scale);
  EXPECT_NEAR(a.energy_change + a.contact + a.numerical, 0.0, 1e-12 * scale);
  // It rolled: v = 5/7 g sin(a) t.
  const double t = 400 * p.time_step;
  EXPECT_NEAR(sim.particles().velocity[0].norm(), 5.0 / 7.0 * kG * std::sin(alpha) * t,
              1e-9 * kG * t);
}

// A sphere on a 50 degree incline with mu = 0.3 slides while it spins up (tan a > 7/2 mu): the
// slip speed grows at g (sin a - 7/2 mu cos a), so the slip work after t is
// mu m g cos(a) * 1/2 g (sin a - 7/2 mu cos a) t^2.
TEST(NscdEnergy, SlippingSphereDissipatesSlipWork) {
  const double alpha = 50.0 * std::numbers::pi / 180.0, mu = 0.3;
  NscdParameters p = nlgs_parameters();
  p.tolerance = 1e-12;
  auto sim = sphere_on_incline(alpha, mu, true, p);
  const int steps = 400;
  const Account a = run(sim, steps);
  const double m = sim.particles().mass[0], t = steps * p.time_step;
  const double expected = mu * m * kG * std::cos(alpha) * 0.5 * kG *
                          (std::sin(alpha) - 3.5 * mu * std::cos(alpha)) * t * t;
  EXPECT_NEAR(a.contact, expected, 1e-9 * expected);
  EXPECT_NEAR(a.energy_change + a.contact + a.numerical, 0.0, 1e-12 * std::abs(a.energy_change));
}

// A sphere launched along the floor without spin slides until it rolls at 5/7 of its speed
// (angular momentum about the contact point is kept): it dissipates m V^2 / 7.
TEST(NscdEnergy, SkiddingSphereDissipatesOneSeventhOfTwiceItsKineticEnergy) {
  ParticleSet set;
  set.add(Vector3d(0, kRadius, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
  const double V = 0.05;  // m/s
  set.velocity[0] = Vector3d(V, 0, 0);
  NscdParameters p = nlgs_parameters();
  p.tolerance = 1e-12;
  NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                     Vector3d(0, -kG, 0), 3, p);
  const Account a = run(sim, 100);  // slides for 2 V / (7 mu g) = 4.9 ms
  const double m = sim.particles().mass[0];
  EXPECT_NEAR(sim.particles().velocity[0].x(), 5.0 / 7.0 * V, 1e-12 * V);
  EXPECT_NEAR(a.contact, m * V * V / 7.0, 1e-9 * m * V * V / 7.0);
  EXPECT_NEAR(a.energy_change, -m * V * V / 7.0, 1e-9 * m * V * V / 7.0);
}

// A sphere dropped onto the floor stops dead (inelastic impact): what it dissipates is all the
// energy it lost, and more than the kinetic energy it arrived with minus one step's fall.
TEST(NscdEnergy, InelasticImpactDissipatesTheEnergyLost) {
  for (double theta : {0.5, 1.0}) {
    ParticleSet set;
    const double height = 5e-3;  // m of free fall before touching
    set.add(Vector3d(0, kRadius + height, 0), kRadius, sphere_mass(kRadius, kDensity), 0);
    NscdParameters p = nlgs_parameters();
    p.theta = theta;
    NscdIntegrator sim(std::move(set), {steel(0.3)}, {Wall::through({0, 0, 0}, {0, 1, 0}, 0)},
                       Vector3d(0, -kG, 0), 3, p);
    const Account a = run(sim, 200);
    const double m = sim.particles().mass[0];
    const double lost = m * kG * (kRadius + height - sim.particles().position[0].y()) -
                        sim.kinetic_energy();
    EXPECT_LT(sim.particles().velocity[0].norm(), 1e-12);
    EXPECT_NEAR(a.contact + a.numerical, lost, 1e-9 * lost) << "theta " << theta;
    EXPECT_NEAR(-a.energy_change, lost, 1e-9 * lost) << "theta " << theta;
    if (theta == 0.5) {
      EXPECT_NEAR(a.contact, m * kG * height, 0.01 * m * kG * height);  // arrival energy
    }
  }
}

// A pile settling in a box (many contacts, friction, impacts, rotation), 2D and 3D: the account
// closes to round-off at theta = 1/2 and at theta = 1.
TEST(NscdEnergy, SettlingPileAccountCloses) {
  for (int dimension : {2, 3}) {
    for (double theta : {0.5, 1.0}) {
      NscdParameters p = nlgs_parameters();
      p.theta = theta;
      p.tolerance = 1e-8;
      auto sim = random_pile(dimension == 3 ? 60 : 40, dimension, 0.3, 7, p);
      const Account a = run(sim, 300);
      const double scale = std::abs(a.energy_change);
      EXPECT_GT(a.contact, 0.0);
      EXPECT_NEAR(a.energy_change + a.contact + a.numerical, 0.0, 1e-11 * scale)
          << "dimension " << dimension << " theta " << theta;
      EXPECT_NEAR(a.contact_listed, a.contact, 1e-11 * scale);
    }
  }
}

// A piston (a body of its own, pushed by a load and its weight) falling onto a column of three
// spheres on the floor: the impacts and the pressed column close the account to round-off, the
// load counting as a constant external force.
TEST(NscdEnergy, PistonOnAColumnAccountCloses) {
  for (double theta : {0.5, 1.0}) {
    ParticleSet set;
    for (int k = 0; k < 3; ++k)
      set.add(Vector3d(0, kRadius * (2 * k + 1), 0), kRadius, sphere_mass(kRadius, kDensity), 0);
    Wall piston = Wall::through({0, 7.0 * kRadius, 0}, {0, -1, 0}, 0);
    piston.make_piston(1e-3, 0.5);  // 1 g, 0.5 N down
    NscdParameters p = nlgs_parameters();
    p.theta = theta;
    p.tolerance = 1e-10;
    NscdIntegrator sim(std::move(set), {steel(0.3)},
                       {Wall::through({0, 0, 0}, {0, 1, 0}, 0), piston}, Vector3d(0, -kG, 0), 3, p);
    const Account a = run(sim, 300);
    EXPECT_GT(a.contact, 0.0);  // the piston's impact
    EXPECT_NEAR(a.energy_change + a.contact + a.numerical, 0.0, 1e-11 * a.contact)
        << "theta " << theta;
  }
}
