// The Zehner-Schlunder-Bauer correlation against its own limits and its primary form.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "coupling/studies/ZehnerSchlunderBauer.h"

namespace tmdem::coupling {
namespace {

// The primary form (Zehner & Schlunder 1970 with Bauer's B: no flattening, continuum gas, no
// radiation), written as it is usually printed: with N = 1 - B / kappa,
//   k / k_f = 1 - sqrt(1 - psi) + 2 sqrt(1 - psi) / N
//             [ (kappa - 1) B / (kappa N^2) ln(kappa / B) - (B + 1) / 2 - (B - 1) / N ].
double primary(double psi, double kappa) {
  const double B = 1.25 * std::pow((1.0 - psi) / psi, 10.0 / 9.0);
  const double N = 1.0 - B / kappa;
  return 1.0 - std::sqrt(1.0 - psi) +
         2.0 * std::sqrt(1.0 - psi) / N *
             ((kappa - 1.0) * B / (kappa * N * N) * std::log(kappa / B) - (B + 1.0) / 2.0 -
              (B - 1.0) / N);
}

ZehnerSchlunderBauerInput bed(double psi, double ks) {
  ZehnerSchlunderBauerInput in;
  in.porosity = psi;
  in.k_solid_W_per_mK = ks;
  in.k_fluid_W_per_mK = 0.0262;
  in.diameter_m = 2e-3;
  return in;
}

TEST(ZehnerSchlunderBauer, SolidLikeTheGasGivesTheGas) {
  for (const double psi : {0.3, 0.4, 0.476, 0.6})
    EXPECT_NEAR(zehner_schlunder_bauer(bed(psi, 0.0262)).k_eff_W_per_mK / 0.0262, 1.0, 1e-12) << psi;
}

TEST(ZehnerSchlunderBauer, ReducesToThePrimaryForm) {
  for (const double psi : {0.36, 0.4, 0.45, 0.558})
    for (const double ks : {0.3, 1.0, 36.0, 50.0}) {
      const double kappa = ks / 0.0262;
      EXPECT_NEAR(zehner_schlunder_bauer(bed(psi, ks)).k_eff_W_per_mK / 0.0262, primary(psi, kappa),
                  1e-11 * primary(psi, kappa))
          << psi << " " << kappa;
    }
}

TEST(ZehnerSchlunderBauer, FlatteningAddsItsShareOfTheSolid) {
  const auto plain = zehner_schlunder_bauer(bed(0.4, 36.0));
  auto in = bed(0.4, 36.0);
  in.flattening = 0.0077;
  const double with = zehner_schlunder_bauer(in).k_eff_W_per_mK / 0.0262;
  const double kp = 36.0 / 0.0262;
  EXPECT_NEAR(with - plain.k_eff_W_per_mK / 0.0262, 0.0077 * std::sqrt(0.6) * (kp - plain.k_c), 1e-9);
}

TEST(ZehnerSchlunderBauer, GasPressureLowersItTowardsTheSolidAlone) {
  // The jump length grows as 1 / pressure: k_eff falls monotonically, to almost nothing for
  // spheres that touch only at points (no flattening, no radiation).
  double previous = zehner_schlunder_bauer(bed(0.4, 1.0)).k_eff_W_per_mK;
  for (const double l : {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2}) {
    auto in = bed(0.4, 1.0);
    in.jump_length_m = l;
    const double k = zehner_schlunder_bauer(in).k_eff_W_per_mK;
    EXPECT_LT(k, previous) << l;
    previous = k;
  }
  auto vacuum = bed(0.4, 1.0);
  vacuum.jump_length_m = 1e3;
  EXPECT_LT(zehner_schlunder_bauer(vacuum).k_eff_W_per_mK, 1e-3 * zehner_schlunder_bauer(bed(0.4, 1.0)).k_eff_W_per_mK);
}

TEST(ZehnerSchlunderBauer, RadiationGrowsWithTheCubeOfTemperature) {
  auto in = bed(0.4, 1.0);
  in.emissivity = 0.9;
  in.temperature_K = 1000.0;
  const auto hot = zehner_schlunder_bauer(in);
  EXPECT_NEAR(hot.k_rad, 4.0 * 5.670374419e-8 / (2.0 / 0.9 - 1.0) * 1e9 * 2e-3 / 0.0262, 1e-12);
  in.temperature_K = 500.0;
  EXPECT_GT(hot.k_eff_W_per_mK, zehner_schlunder_bauer(in).k_eff_W_per_mK);
  EXPECT_THROW(zehner_schlunder_bauer(bed(1.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(zehner_schlunder_bauer(bed(0.4, -1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace tmdem::coupling
