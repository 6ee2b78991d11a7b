// Validation of beds in gas (docs/validation.md): bulk beds against the Zehner-Schlunder-Bauer
// correlation. Each material's bed (540 spheres of 1 mm radius, laid by deposition into a box
// periodic along x and z, 6 diameters each way, then pressed by a piston at 1e3 Pa and settled)
// is built once and exported; each gas is then a conductivity study of that bed, imported, with
// the recommended settings (surrounding_layer, the particles' own resistance with an isothermal
// core of 0.62 r). The reference is ZSB at the study's porosity with the VDI Heat Atlas'
// flattening coefficient 0.0077 and the Smoluchowski factor of the gas at 1 bar; each row's
// figures are printed ([ valid    ] lines) and docs/validation.md carries them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "E2eSupport.h"
#include "coupling/studies/ZehnerSchlunderBauer.h"

using namespace tmdem::e2e;

namespace {

struct Solid {
  const char* name;
  double conductivity_W_per_mK, young_modulus_Pa, poisson_ratio, density_kg_m3;
};
struct Gas {
  const char* name;
  double conductivity_W_per_mK, mean_free_path_m, accommodation;
};
const Gas kAir{"air", 0.0262, 6.8e-8, 0.9};
const Gas kHelium{"helium", 0.152, 1.9e-7, 0.9};

// How close tmdem must come to ZSB for one gas: [low, high] of k_tmdem / k_ZSB.
struct Band {
  double low, high;
};
struct BedRow {
  Solid solid;
  Band air, helium;
  bool pressures = false;  // also k_eff against the air's pressure (glass)
  // Laid and settled without friction (then pressed and studied with it): a dense bed, core
  // porosity near random close packing (0.366 measured), 0.385 between floor and piston.
  bool dense = false;
};

constexpr double kPeriod = 0.012;  // m
constexpr double kParticleRadius = 0.001;  // m

std::string bed_scene(const Solid& s, const std::string& particles, double piston_y_m,
                      double friction = 0.3) {
  std::ostringstream t;
  t.precision(17);
  t << "format = \"tmdem-scene-1\"\n"
    << "[simulation]\nduration = 1.0\ngravity = [0.0, -9.81, 0.0]\nseed = 5\n"
    << "[periodic]\nx = [0.0, " << kPeriod << "]\nz = [0.0, " << kPeriod << "]\n"
    << "[effects]\nmechanics = \"settle\"\n"
    << "[[material]]\nname = \"solid\"\ndensity = " << s.density_kg_m3
    << "\nyoung_modulus = " << s.young_modulus_Pa << "\npoisson_ratio = " << s.poisson_ratio
    << "\nfriction = " << friction << "\nrolling_friction = " << (friction > 0.0 ? 0.1 : 0.0)
    << "\nconductivity = " << s.conductivity_W_per_mK
    << "\nheat_capacity = 800.0\n"
    << particles
    << "[[wall]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"solid\"\n"
    << "temperature = 310.0\n";
  if (piston_y_m > 0.0)
    t << "[[wall]]\npoint = [0.0, " << piston_y_m << ", 0.0]\nnormal = [0.0, -1.0, 0.0]\n"
      << "material = \"solid\"\ntemperature = 290.0\npiston = true\nmass = 0.002\n"
      << "pressure = 1000.0\npressure_area = " << kPeriod * kPeriod << "\n";
  return t.str();
}

std::vector<std::string> csv_row(const std::string& path) {
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  std::vector<std::string> cells;
  std::istringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  return cells;
}

class Validation : public ::testing::TestWithParam<BedRow> {};

TEST_P(Validation, BulkBedInAirAndHeliumAgainstZehnerSchlunderBauer) {
  const BedRow& row = GetParam();
  const auto dir = scratch_dir(std::string("validation_") + row.solid.name + (row.dense ? "_dense" : ""));
  // 1. Lay and settle the bed once under its weight (a piston falling onto it from the box's top
  // would cost far more: its landing shakes the whole column).
  const std::string deposit =
      "[[generate]]\nkind = \"deposit\"\ncount = 540\nradius = 0.001\nmaterial = \"solid\"\n"
      "box = { min = [0.0, 0.0, 0.0], max = [0.012, 0.0315, 0.012] }\n";
  write_file(dir + "/lay.toml", bed_scene(row.solid, deposit, -1.0, row.dense ? 0.0 : 0.3));
  auto r = run_tmdem("run lay.toml -o lay.h5 --quiet --summary lay.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(read_summary(dir + "/lay.json")["settle"]["at_rest"].get<bool>());
  r = run_tmdem("export lay.h5 -o laid.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The top of an exported bed (y + r of its highest sphere), m.
  const auto top_of = [&](const std::string& csv) {
    double top_m = 0.0;
    std::ifstream in(dir + "/" + csv);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::istringstream cells(line);
      std::string x, y;
      std::getline(cells, x, ',');
      std::getline(cells, y, ',');
      top_m = std::max(top_m, std::stod(y) + kParticleRadius);
    }
    return top_m;
  };
  // 2. Pressed once by the piston laid on its top (1e3 Pa) and settled again.
  // The position step holds overlaps up to twice the slop (2e-4 of the radius) to its own 1%
  // tolerance: a pressed bed's deepest can be a hair over 2e-4 (2.003e-4 measured).
  const auto imported = [](const std::string& csv) {
    return "[[import]]\nfile = \"" + csv + "\"\noverlap_tolerance = 2.5e-4\n";
  };
  write_file(dir + "/press.toml", bed_scene(row.solid, imported("laid.csv"), top_of("laid.csv") + 1e-6));
  r = run_tmdem("run press.toml -o press.h5 --quiet --summary press.json --set simulation.duration=0.001", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(read_summary(dir + "/press.json")["settle"]["at_rest"].get<bool>());
  r = run_tmdem("export press.h5 -o bed.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double top_m = top_of("bed.csv");
  ASSERT_GT(top_m, 0.02);
  // 3. The pressed bed, imported with the piston on its top (it re-settles in a few steps), in
  // each gas.
  // One conductivity study of the pressed bed in `gas` at `pressure_Pa` (0: continuum):
  // {k_eff, porosity}.
  std::string last_output;  // of the last study (its report prints ZSB beside k_eff)
  const auto study = [&](const Gas& gas, double pressure_Pa) -> std::pair<double, double> {
    std::ostringstream settings;
    settings << "[fluid]\nmodel = \"surrounding_layer\"\nconductivity = " << gas.conductivity_W_per_mK
             << "\nmean_free_path = " << gas.mean_free_path_m << "\naccommodation = " << gas.accommodation
             << "\npressure = " << pressure_Pa << "\n"
             << "[thermal]\nparticle_resistance = \"isothermal_core\"\ncore_fraction = 0.62\n";
    std::string scene = bed_scene(row.solid, imported("bed.csv"), top_m + 1e-6);
    scene.replace(scene.find("[effects]\nmechanics = \"settle\"\n"), 31,
                  "[effects]\nmechanics = \"settle\"\ngas_conduction = true\n");
    write_file(dir + "/bed.toml", scene + settings.str());
    const std::string csv = std::string(gas.name) + ".csv";
    const auto result = run_tmdem("study conductivity bed.toml --csv " + csv, dir);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    last_output = result.output;
    const auto cells = csv_row(dir + "/" + csv);
    if (cells.size() < 7) {
      ADD_FAILURE() << "no study row in " << csv;
      return {0.0, 0.5};
    }
    return {std::stod(cells[1]), std::stod(cells[5])};
  };
  // ZSB at `porosity` with the VDI's flattening coefficient (or `flattening`) and the
  // Smoluchowski factor of `gas` at `pressure_Pa` (0: continuum), W/(m K).
  const auto zsb = [&](const Gas& gas, double porosity, double pressure_Pa, double flattening) {
    tmdem::coupling::ZehnerSchlunderBauerInput in;
    in.porosity = porosity;
    in.k_solid_W_per_mK = row.solid.conductivity_W_per_mK;
    in.k_fluid_W_per_mK = gas.conductivity_W_per_mK;
    in.diameter_m = 2.0 * kParticleRadius;
    in.flattening = flattening;
    in.jump_length_m = pressure_Pa > 0.0 ? 2.0 * (2.0 - gas.accommodation) / gas.accommodation *
                                               gas.mean_free_path_m * 101325.0 / pressure_Pa
                                         : 0.0;
    return tmdem::coupling::zehner_schlunder_bauer(in).k_eff_W_per_mK;
  };
  for (const auto& [gas, band] : {std::pair{kAir, row.air}, std::pair{kHelium, row.helium}}) {
    const auto [k, porosity] = study(gas, 0.0);
    const double reference = zsb(gas, porosity, 101325.0, 0.0077);
    const double plain = zsb(gas, porosity, 101325.0, 0.0);
    std::printf("[ valid    ] %s%s in %s: k_s/k_f %.1f, porosity %.4f, k_eff %.4f W/(m K), ZSB %.4f "
                "(tmdem/ZSB %.3f), ZSB without flattening %.4f (%.3f)\n",
                row.solid.name, row.dense ? " (dense)" : "", gas.name,
                row.solid.conductivity_W_per_mK / gas.conductivity_W_per_mK,
                porosity, k, reference, k / reference, plain, k / plain);
    EXPECT_GE(porosity, 0.36);
    EXPECT_LE(porosity, row.dense ? 0.40 : 0.45);
    EXPECT_GE(k / reference, band.low) << gas.name;
    EXPECT_LE(k / reference, band.high) << gas.name;
  }
  if (!row.pressures) return;
  // k_eff against the air's pressure: each ratio to the continuum value, tmdem's against
  // ZSB's (both fall as the gaps' temperature jumps grow). Within 20% of ZSB at 1e4 Pa; lower
  // down tmdem falls about a decade and a half earlier (measured 0.59 of ZSB at 100 Pa): the
  // surrounding layer adds the jump to each local gap, which near a contact is far thinner than
  // the diameter ZSB sets it against. The 100 Pa band pins that miss.
  const auto [k_continuum, porosity] = study(kAir, 0.0);
  double previous = k_continuum;
  for (const auto& [pressure, band] : {std::pair{1e4, Band{0.8, 1.2}}, std::pair{1e2, Band{0.5, 0.7}}}) {
    const double k = study(kAir, pressure).first;
    const double reference = zsb(kAir, porosity, pressure, 0.0077);
    std::printf("[ valid    ] %s in air at %g Pa: k_eff %.4f W/(m K) (%.3f of the continuum), ZSB %.4f "
                "(%.3f of its continuum), tmdem/ZSB %.3f\n",
                row.solid.name, pressure, k, k / k_continuum, reference,
                reference / zsb(kAir, porosity, 0.0, 0.0077), k / reference);
    EXPECT_LT(k, previous) << pressure;
    // The study's own report gives the same ZSB (and ratio) as this test computes.
    const auto at = last_output.find("k_eff / ZSB = ");
    ASSERT_NE(at, std::string::npos) << last_output;
    EXPECT_NEAR(std::stod(last_output.substr(at + 14)), k / reference, 1e-5) << pressure;
    EXPECT_GE(k / reference, band.low) << pressure;
    EXPECT_LE(k / reference, band.high) << pressure;
    previous = k;
  }
}

// The bands: within 20% of ZSB where tmdem meets the target. Three rows miss it and their bands
// pin the miss as measured (about +- 0.07), so a change that moves it shows (docs/validation.md):
// - alumina and steel in air (k_s / k_f over 1,000), 0.72 and 0.61: there ZSB's flattening term
//   (phi k_p sqrt(1 - psi), a flattened contact of about 0.09 r) carries a third of the heat,
//   and the Hertz contacts of smooth spheres at 1e3 Pa (a of about 0.001 r) carry less; without
//   that term ZSB gives 0.34 and 0.37 W/(m K), and tmdem lands at 1.08 and 1.09 of it;
// - glass in helium (k_s / k_f 6.6, below the range of 10 to 2,000), 0.76 loose (the
//   dense bed lands inside at 0.87, but at 0.73 when laid along another path: docs/validation.md): the lumped
//   shell of the isothermal core is too resistive when the gas conducts nearly as well as the
//   solid, and no one core fraction serves both glass rows (0.65: air 1.21, helium 0.84; 0.62:
//   air 1.14, helium 0.75); 0.62 keeps the commoner case, glass beads in air, inside.
INSTANTIATE_TEST_SUITE_P(
    Beds, Validation,
    ::testing::Values(BedRow{{"glass", 1.0, 6.3e10, 0.2, 2500.0}, {0.8, 1.2}, {0.68, 0.82}, true},
                      BedRow{{"alumina", 30.0, 3.7e11, 0.22, 3900.0}, {0.65, 0.8}, {0.8, 1.2}},
                      BedRow{{"steel", 50.0, 2.1e11, 0.3, 7800.0}, {0.56, 0.7}, {0.8, 1.2}},
                      BedRow{{"glass", 1.0, 6.3e10, 0.2, 2500.0}, {0.8, 1.2}, {0.8, 1.2}, false, true}),
    [](const auto& info) {
      return std::string(info.param.solid.name) + (info.param.dense ? "_dense" : "");
    });

}  // namespace
