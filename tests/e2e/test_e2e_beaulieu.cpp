// Validation against a measurement: examples/heated_bed_beaulieu.toml run as it is (the bed
// laid and settled, then 4000 s of heating; a few seconds on one core, most of it the settle)
// must describe Beaulieu's experiment and reproduce its three thermocouples at 4000 s within
// 1 K (docs/validation.md, "Beaulieu's heated packed bed"). The figures it checks against are
// the experiment's (C. Beaulieu, PhD thesis, Polytechnique Montreal, 2020, as Lethe's example
// examples/dem-mp/3d-heated-packed-bed gives them), not tmdem's; the probes' readings are
// printed on the [ valid    ] line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The experiment.
constexpr int kSpheres = 8849;
constexpr double kDiameter_m = 6.4e-3;
constexpr double kDensity_kg_m3 = 7747.0;
constexpr double kHeatCapacity_J_kgK = 464.0;
constexpr double kStart_K = 293.15;  // 20 C
constexpr double kPlate_K = 326.15;  // 53 C
constexpr double kHeating_s = 4000.0;
constexpr double kKelvinAt0C = 273.15;
// Thermocouples: distance from the plate (m) and reading at 4000 s (C), from the measured curves
// (reference/steel_Beaulieu_0.040_experiment.csv, ..._0.060_..., ..._0.073_...).
struct Thermocouple {
  double depth_m, at_4000s_C;
};
constexpr Thermocouple kThermocouples[] = {{0.040, 33.2}, {0.060, 26.3}, {0.073, 23.9}};
constexpr double kBand_K = 1.0;  // the validation's target

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

TEST(ValidationBeaulieu, ExampleReproducesTheThermocouplesWithinAKelvin) {
  const auto dir = scratch_dir("beaulieu");
  const auto r = run_tmdem(std::string("run '") + TMDEM_SOURCE_DIR +
                               "/examples/heated_bed_beaulieu.toml' -o out.h5 --quiet --summary s.json",
                           dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  EXPECT_EQ(s["status"].get<std::string>(), "ok");
  EXPECT_TRUE(s["settle"]["at_rest"].get<bool>());
  EXPECT_EQ(s["mechanics"]["unconverged_steps"].get<std::int64_t>(), 0);
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
  EXPECT_DOUBLE_EQ(s["simulated_time_s"].get<double>(), kHeating_s);

  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  // The spheres: Beaulieu's count, size, mass and heat capacity, all at 20 C.
  const auto radius = read_doubles(f, "/particles/radius");
  const auto mass = read_doubles(f, "/particles/mass");
  const auto capacity = read_doubles(f, "/particles/heat_capacity");
  ASSERT_EQ(radius.size(), std::size_t(kSpheres));
  const double r_m = kDiameter_m / 2.0;
  const double m_kg = kDensity_kg_m3 * 4.0 / 3.0 * M_PI * r_m * r_m * r_m;
  const auto times = read_doubles(f, "/frames/time");
  const auto temperature = read_doubles(f, "/frames/temperature");
  ASSERT_EQ(temperature.size(), times.size() * std::size_t(kSpheres));
  for (int i = 0; i < kSpheres; ++i) {
    ASSERT_DOUBLE_EQ(radius[i], r_m) << i;
    ASSERT_NEAR(mass[i], m_kg, 1e-12 * m_kg) << i;
    ASSERT_NEAR(capacity[i], m_kg * kHeatCapacity_J_kgK, 1e-12 * m_kg * kHeatCapacity_J_kgK) << i;
    ASSERT_DOUBLE_EQ(temperature[i], kStart_K) << i;
  }

  // One wall held at 53 C (the plate), the others adiabatic; the box's axis from its side walls.
  std::vector<hsize_t> dims;
  const auto wall_point = read_doubles(f, "/walls/point", &dims);
  const auto wall_normal = read_doubles(f, "/walls/normal");
  const auto wall_T = read_doubles(f, "/walls/temperature");
  int plate = -1;
  double low[2] = {-INFINITY, -INFINITY}, high[2] = {INFINITY, INFINITY};
  for (std::size_t w = 0; w < wall_T.size(); ++w) {
    if (std::isfinite(wall_T[w])) {
      EXPECT_EQ(plate, -1) << "a second isothermal wall: " << w;
      plate = int(w);
      EXPECT_DOUBLE_EQ(wall_T[w], kPlate_K);
    }
    for (int k = 0; k < 2; ++k) {
      if (wall_normal[3 * w + k] > 0.5) low[k] = wall_point[3 * w + k];
      if (wall_normal[3 * w + k] < -0.5) high[k] = wall_point[3 * w + k];
    }
  }
  ASSERT_GE(plate, 0);
  EXPECT_NEAR(high[0] - low[0], 0.105, 1e-12);  // the 10.5 x 10 cm footprint
  EXPECT_NEAR(high[1] - low[1], 0.100, 1e-12);
  const double axis[2] = {(low[0] + high[0]) / 2.0, (low[1] + high[1]) / 2.0};

  // The probes: a box of 4 d x 4 d x 2 d near the axis at each thermocouple's distance from the
  // plate (as Lethe's example samples its bed).
  const auto probe_point = read_doubles(f, "/probes/point");
  const auto probe_box = read_doubles(f, "/probes/box");
  const auto count = read_ints(f, "/probes/count");
  const auto mean_K = read_doubles(f, "/probes/mean_K");
  constexpr std::size_t kProbes = std::size(kThermocouples);
  ASSERT_EQ(probe_point.size(), 3 * kProbes);
  ASSERT_EQ(mean_K.size(), times.size() * kProbes);
  EXPECT_DOUBLE_EQ(times.back(), kHeating_s);
  const std::size_t last = times.size() - 1;
  std::string figures;
  for (std::size_t p = 0; p < kProbes; ++p) {
    const double* c = &probe_point[3 * p];
    const double from_plate[3] = {c[0] - wall_point[3 * plate], c[1] - wall_point[3 * plate + 1],
                                  c[2] - wall_point[3 * plate + 2]};
    EXPECT_NEAR(dot3(from_plate, &wall_normal[3 * plate]), kThermocouples[p].depth_m, 1e-12) << p;
    EXPECT_LE(std::hypot(c[0] - axis[0], c[1] - axis[1]), kDiameter_m) << p;
    EXPECT_NEAR(probe_box[3 * p + 0], 4.0 * kDiameter_m, 1e-12) << p;
    EXPECT_NEAR(probe_box[3 * p + 1], 4.0 * kDiameter_m, 1e-12) << p;
    EXPECT_NEAR(probe_box[3 * p + 2], 2.0 * kDiameter_m, 1e-12) << p;
    EXPECT_GT(count[last * kProbes + p], 0) << p;
    const double model_C = mean_K[last * kProbes + p] - kKelvinAt0C;
    EXPECT_NEAR(model_C, kThermocouples[p].at_4000s_C, kBand_K)
        << "thermocouple at " << kThermocouples[p].depth_m << " m";
    char line[128];
    std::snprintf(line, sizeof line, "%s%.1f cm %.2f C (measured %.1f)", p ? ", " : "",
                  100.0 * kThermocouples[p].depth_m, model_C, kThermocouples[p].at_4000s_C);
    figures += line;
  }
  std::printf("[ valid    ] Beaulieu's heated bed at 4000 s: %s\n", figures.c_str());
}
