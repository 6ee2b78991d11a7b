// Validation of beds in gas (docs/validation.md): bulk beds against the Zehner-Schlunder-Bauer
// correlation. Each material's bed (540 spheres of 1 mm radius, laid by deposition into a box
// periodic along x and z, 6 diameters each way, then pressed by a piston at 1e3 Pa and settled)
// is built once and exported; each gas is then a conductivity study of that bed, imported, with
// the recommended settings (surrounding_layer, the particles' own resistance with an isothermal
// core of 0.62 r, contact spots flattened to at least 0.025 R*). The reference is ZSB at the
// study's porosity with the VDI Heat Atlas' flattening coefficient 0.0077 and the Smoluchowski
// factor of the gas at 1 bar; each row's figures are printed ([ valid    ] lines) and
// docs/validation.md carries them.
// ValidationRadiation: the glass bed in vacuum with radiation between particles and walls,
// enclosed, against ZSB's vacuum limit (a miss the model explains; docs/validation.md
// "Radiation in vacuum").
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
                      double friction = 0.3, double T_hot_K = 310.0, double T_cold_K = 290.0) {
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
    << "temperature = " << T_hot_K << "\n";
  if (piston_y_m > 0.0)
    t << "[[wall]]\npoint = [0.0, " << piston_y_m << ", 0.0]\nnormal = [0.0, -1.0, 0.0]\n"
      << "material = \"solid\"\ntemperature = " << T_cold_K << "\npiston = true\nmass = 0.002\n"
      << "pressure = 1000.0\npressure_area = " << kPeriod * kPeriod << "\n";
  return t.str();
}

// The study CSV's first row, cell by cell, and with its header as `names`.
std::vector<std::string> csv_row(const std::string& path,
                                 std::vector<std::string>* names = nullptr) {
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  if (names != nullptr) {
    std::istringstream head(header);
    for (std::string name; std::getline(head, name, ',');) names->push_back(name);
  }
  std::vector<std::string> cells;
  std::istringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  return cells;
}

// The [[import]] of an exported bed. The position step holds overlaps up to twice the slop
// (2e-4 of the radius) to its own 1% tolerance, but the pressed glass bed's steps end with
// overlaps up to 3.0e-4 of the radius (the summary's max_penetration_m, 2026-12-01, the code
// before and after honest convergence checked within its runs alike), and its last frame's
// deepest was 2.003e-4 when first measured and 2.58e-4 now: the import accepts what a run
// of this bed leaves.
std::string imported(const std::string& csv) {
  return "[[import]]\nfile = \"" + csv + "\"\noverlap_tolerance = 4e-4\n";
}

// Lays 540 spheres of `solid` in `dir` (without friction when `dense`), settles them, presses
// them with the piston at 1e3 Pa and settles again: dir/bed.csv, its top (y + r of the highest
// sphere) in top_m.
void lay_and_press(const Solid& solid, const std::string& dir, bool dense, double& top_m) {
  // 1. Lay and settle the bed once under its weight (a piston falling onto it from the box's top
  // would cost far more: its landing shakes the whole column).
  const std::string deposit =
      "[[generate]]\nkind = \"deposit\"\ncount = 540\nradius = 0.001\nmaterial = \"solid\"\n"
      "box = { min = [0.0, 0.0, 0.0], max = [0.012, 0.0315, 0.012] }\n";
  write_file(dir + "/lay.toml", bed_scene(solid, deposit, -1.0, dense ? 0.0 : 0.3));
  auto r = run_tmdem("run lay.toml -o lay.h5 --quiet --summary lay.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(read_summary(dir + "/lay.json")["settle"]["at_rest"].get<bool>());
  r = run_tmdem("export lay.h5 -o laid.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The top of an exported bed (y + r of its highest sphere), m.
  const auto top_of = [&](const std::string& csv) {
    double highest_m = 0.0;
    std::ifstream in(dir + "/" + csv);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::istringstream cells(line);
      std::string x, y;
      std::getline(cells, x, ',');
      std::getline(cells, y, ',');
      highest_m = std::max(highest_m, std::stod(y) + kParticleRadius);
    }
    return highest_m;
  };
  // 2. Pressed once by the piston laid on its top (1e3 Pa) and settled again.
  write_file(dir + "/press.toml", bed_scene(solid, imported("laid.csv"), top_of("laid.csv") + 1e-6));
  r = run_tmdem("run press.toml -o press.h5 --quiet --summary press.json --set simulation.duration=0.001", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(read_summary(dir + "/press.json")["settle"]["at_rest"].get<bool>());
  r = run_tmdem("export press.h5 -o bed.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  top_m = top_of("bed.csv");
  ASSERT_GT(top_m, 0.02);
}

class Validation : public ::testing::TestWithParam<BedRow> {};

TEST_P(Validation, BulkBedInAirAndHeliumAgainstZehnerSchlunderBauer) {
  const BedRow& row = GetParam();
  const auto dir = scratch_dir(std::string("validation_") + row.solid.name + (row.dense ? "_dense" : ""));
  double top_m = 0.0;
  ASSERT_NO_FATAL_FAILURE(lay_and_press(row.solid, dir, row.dense, top_m));
  // 3. The pressed bed, imported with the piston on its top (it re-settles in a few steps), in
  // each gas.
  // One conductivity study of the pressed bed in `gas` at `pressure_Pa` (0: continuum): between
  // the walls and in the bulk (centres more than two diameters from both walls).
  struct Measured {
    double k_eff = 0.0, porosity = 0.5, k_bulk = 0.0, porosity_bulk = 0.5;
  };
  std::string last_output;  // of the last study (its report prints ZSB beside k_bulk)
  const auto study = [&](const Gas& gas, double pressure_Pa) -> Measured {
    std::ostringstream settings;
    settings << "[fluid]\nmodel = \"surrounding_layer\"\nconductivity = " << gas.conductivity_W_per_mK
             << "\nmean_free_path = " << gas.mean_free_path_m << "\naccommodation = " << gas.accommodation
             << "\npressure = " << pressure_Pa << "\n"
             << "[thermal]\nparticle_resistance = \"isothermal_core_rays\"\ncore_fraction = 0.65\n"
             << "contact_flattening = 0.02\n";
    std::string scene = bed_scene(row.solid, imported("bed.csv"), top_m + 1e-6);
    scene.replace(scene.find("[effects]\nmechanics = \"settle\"\n"), 31,
                  "[effects]\nmechanics = \"settle\"\ngas_conduction = true\n");
    write_file(dir + "/bed.toml", scene + settings.str());
    const std::string csv = std::string(gas.name) + ".csv";
    const auto result = run_tmdem("study conductivity bed.toml --csv " + csv, dir);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    last_output = result.output;
    std::vector<std::string> names;
    const auto cells = csv_row(dir + "/" + csv, &names);
    const auto cell = [&](const std::string& name) {
      const auto at = std::find(names.begin(), names.end(), name);
      const auto i = std::size_t(at - names.begin());
      if (at == names.end() || i >= cells.size() || cells[i].empty()) {
        ADD_FAILURE() << "no " << name << " in " << csv;
        return 0.5;
      }
      return std::stod(cells[i]);
    };
    return {cell("k_eff_W_per_mK"), cell("porosity"), cell("k_bulk_W_per_mK"), cell("porosity_bulk")};
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
    const Measured m = study(gas, 0.0);
    const double reference = zsb(gas, m.porosity_bulk, 101325.0, 0.0077);
    const double whole = zsb(gas, m.porosity, 101325.0, 0.0077);
    std::printf("[ valid    ] %s%s in %s: k_s/k_f %.1f, bulk porosity %.4f, k_bulk %.4f W/(m K), ZSB %.4f "
                "(tmdem/ZSB %.3f); between the walls porosity %.4f, k_eff %.4f, ZSB %.4f (%.3f)\n",
                row.solid.name, row.dense ? " (dense)" : "", gas.name,
                row.solid.conductivity_W_per_mK / gas.conductivity_W_per_mK, m.porosity_bulk,
                m.k_bulk, reference, m.k_bulk / reference, m.porosity, m.k_eff, whole,
                m.k_eff / whole);
    EXPECT_GE(m.porosity_bulk, 0.36);
    EXPECT_LE(m.porosity_bulk, 0.45);
    EXPECT_GE(m.k_bulk / reference, band.low) << gas.name;
    EXPECT_LE(m.k_bulk / reference, band.high) << gas.name;
    // The wall layers conduct worse than the bulk: between the walls k_eff is lower.
    EXPECT_LT(m.k_eff, m.k_bulk) << gas.name;
  }
  if (!row.pressures) return;
  // k_bulk against the air's pressure: each ratio to the continuum value, tmdem's against
  // ZSB's (both fall as the gaps' temperature jumps grow). Within 20% of ZSB at 1e4 Pa; lower
  // down tmdem falls earlier: the surrounding layer adds the jump to each local gap, which near
  // a contact is far thinner than the diameter ZSB sets it against. The 100 Pa band pins that
  // miss (docs/validation.md "Gas pressure").
  const Measured continuum = study(kAir, 0.0);
  double previous = continuum.k_bulk;
  for (const auto& [pressure, band] : {std::pair{1e4, Band{0.8, 1.2}}, std::pair{1e2, Band{0.8, 1.2}}}) {
    const double k = study(kAir, pressure).k_bulk;
    const double reference = zsb(kAir, continuum.porosity_bulk, pressure, 0.0077);
    std::printf("[ valid    ] %s in air at %g Pa: k_bulk %.4f W/(m K) (%.3f of the continuum), ZSB %.4f "
                "(%.3f of its continuum), tmdem/ZSB %.3f\n",
                row.solid.name, pressure, k, k / continuum.k_bulk, reference,
                reference / zsb(kAir, continuum.porosity_bulk, 0.0, 0.0077), k / reference);
    EXPECT_LT(k, previous) << pressure;
    // The study's own report gives the same ZSB (and ratio) as this test computes.
    const auto at = last_output.find("k_bulk / ZSB = ");
    ASSERT_NE(at, std::string::npos) << last_output;
    EXPECT_NEAR(std::stod(last_output.substr(at + 15)), k / reference, 1e-5) << pressure;
    EXPECT_GE(k / reference, band.low) << pressure;
    EXPECT_LE(k / reference, band.high) << pressure;
    previous = k;
  }
}

// The bands: within 20% of ZSB (docs/validation.md). core_fraction 0.65 and contact_flattening
// 0.02 were chosen on these ten rows (bulk), so the rows check that one pair of values serves
// three solids, two gases and two porosities, not an independent prediction.
INSTANTIATE_TEST_SUITE_P(
    Beds, Validation,
    ::testing::Values(BedRow{{"glass", 1.0, 6.3e10, 0.2, 2500.0}, {0.8, 1.2}, {0.8, 1.2}, true},
                      BedRow{{"alumina", 30.0, 3.7e11, 0.22, 3900.0}, {0.8, 1.2}, {0.8, 1.2}},
                      BedRow{{"steel", 50.0, 2.1e11, 0.3, 7800.0}, {0.8, 1.2}, {0.8, 1.2}},
                      BedRow{{"glass", 1.0, 6.3e10, 0.2, 2500.0}, {0.8, 1.2}, {0.8, 1.2}, false, true},
                      BedRow{{"steel", 50.0, 2.1e11, 0.3, 7800.0}, {0.8, 1.2}, {0.8, 1.2}, false, true}),
    [](const auto& info) {
      return std::string(info.param.solid.name) + (info.param.dense ? "_dense" : "");
    });


// Radiation between particles in vacuum (docs/validation.md "Radiation in vacuum"): the pressed
// glass bed (emissivity 0.9, no gas) at 800, 1000 and 1200 K, its walls 5 K apart, enclosed
// ([radiation] surroundings = false: each particle's view factors to its neighbours and walls
// within pair_cutoff scaled to sum to 1; the walls radiate; pairs whose centre line a third
// sphere crosses do not exchange), pair_cutoff 4 as the docs recommend, against ZSB's vacuum
// limit. ZSB without gas is its k_G -> 0 limit (a jump length of 1e6 diameters): the gas path
// vanishes and, k_rad being a conductivity that does not depend on the gap, the unit cell keeps
// no logarithm,
//   k_eff = (1 - sqrt(1-psi)) psi k_rad + sqrt(1-psi) [phi k_s + (1-phi) (B+1)/B k_rad k_s / (k_s + k_rad)]
// with k_rad = 4 sigma / (2/eps - 1) T^3 d, in W/(m K) and independent of k_f (checked here).
// Compared in the bulk, as the gas rows, with the particles' own resistance of the recommended
// settings (isothermal_core_rays, core 0.65 r): the shells stand in series with the radiative
// exchange as ZSB puts the glass in series with k_rad, so radiation's part grows less than T^3
// (measured 2.80 from 800 to 1200 K against ZSB's 2.49 and T^3's 3.375). tmdem lands at 0.94,
// 0.99 and 1.05 of ZSB (measured); the bands pin those ratios (+-0.06), so a change shows.
TEST(ValidationRadiation, GlassBedInVacuumAt800To1200KAgainstZehnerSchlunderBauerRadiativeTerm) {
  const Solid glass{"glass", 1.0, 6.3e10, 0.2, 2500.0};
  constexpr double kEmissivity = 0.9;
  const auto dir = scratch_dir("validation_radiation");
  double top_m = 0.0;
  ASSERT_NO_FATAL_FAILURE(lay_and_press(glass, dir, false, top_m));
  // One study at mean temperature T_K: the CSV's cells by column name.
  const auto study = [&](double T_K, bool radiation) {
    std::string scene = bed_scene(glass, imported("bed.csv"), top_m + 1e-6, 0.3, T_K + 2.5, T_K - 2.5);
    if (radiation) {
      scene.replace(scene.find("[effects]\nmechanics = \"settle\"\n"), 31,
                    "[effects]\nmechanics = \"settle\"\nradiation = true\n");
      scene.replace(scene.find("heat_capacity = 800.0\n"), 22,
                    "heat_capacity = 800.0\nemissivity = " + std::to_string(kEmissivity) + "\n");
      scene += "[radiation]\nbetween_particles = true\nsurroundings = false\npair_cutoff = 4.0\n"
               "[thermal]\nlinear_solver = \"klu\"\n";
    } else {
      scene += "[thermal]\n";
    }
    scene += "particle_resistance = \"isothermal_core_rays\"\ncore_fraction = 0.65\n";
    write_file(dir + "/vacuum.toml", scene);
    const auto result = run_tmdem("study conductivity vacuum.toml --csv vacuum.csv", dir);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    std::vector<std::string> names;
    const auto cells = csv_row(dir + "/vacuum.csv", &names);
    return [names, cells](const std::string& column) {
      const auto at = std::find(names.begin(), names.end(), column);
      if (at == names.end() || std::size_t(at - names.begin()) >= cells.size()) {
        ADD_FAILURE() << "no column " << column;
        return 0.0;
      }
      return std::stod(cells[std::size_t(at - names.begin())]);
    };
  };
  // ZSB in vacuum at `porosity` and T_K (jump length `jump_diameters` diameters, gas k_f), W/(m K).
  const auto zsb = [&](double porosity, double T_K, double jump_diameters = 1e6, double k_f = 0.0262) {
    tmdem::coupling::ZehnerSchlunderBauerInput in;
    in.porosity = porosity;
    in.k_solid_W_per_mK = glass.conductivity_W_per_mK;
    in.k_fluid_W_per_mK = k_f;
    in.diameter_m = 2.0 * kParticleRadius;
    in.flattening = 0.0077;
    in.jump_length_m = jump_diameters * in.diameter_m;
    in.emissivity = kEmissivity;
    in.temperature_K = T_K;
    return tmdem::coupling::zehner_schlunder_bauer(in).k_eff_W_per_mK;
  };
  // The vacuum limit: converged in the jump length, independent of k_f, the closed form above.
  for (const double T_K : {800.0, 1200.0}) {
    const double psi = 0.443, k_rad = 4.0 * 5.670374419e-8 / (2.0 / kEmissivity - 1.0) * std::pow(T_K, 3) * 2e-3;
    const double B = 1.25 * std::pow((1.0 - psi) / psi, 10.0 / 9.0), root = std::sqrt(1.0 - psi);
    const double closed = (1.0 - root) * psi * k_rad +
                          root * (0.0077 * 1.0 + (1.0 - 0.0077) * (B + 1.0) / B * k_rad / (1.0 + k_rad));
    EXPECT_NEAR(zsb(psi, T_K), closed, 1e-5 * closed) << T_K;
    EXPECT_NEAR(zsb(psi, T_K, 1e9), closed, 1e-6 * closed) << T_K;
    EXPECT_NEAR(zsb(psi, T_K, 1e6, 1.0), closed, 1e-5 * closed) << T_K;
  }
  // Contacts alone (radiation off): subtracted from each k_bulk for the trend.
  const double k_contacts = study(1000.0, false)("k_bulk_W_per_mK");
  struct Row {
    double T_K;
    Band band;  // of k_bulk / k_ZSB: as measured (0.944, 0.995, 1.051), +- 0.06
  };
  double k_800 = 0.0, k_1200 = 0.0, zsb_800 = 0.0, zsb_1200 = 0.0;
  for (const Row& row : {Row{800.0, {0.88, 1.0}}, Row{1000.0, {0.93, 1.06}}, Row{1200.0, {0.99, 1.11}}}) {
    const auto cell = study(row.T_K, true);
    const double k = cell("k_bulk_W_per_mK"), porosity = cell("porosity_bulk");
    const double reference = zsb(porosity, row.T_K);
    std::printf("[ valid    ] glass in vacuum at %.0f K: bulk porosity %.4f, k_bulk %.4f W/(m K) "
                "(contacts alone %.4f), ZSB %.4f (tmdem/ZSB %.3f); between the walls k_eff %.4f, "
                "ZSB %.4f (%.3f); shares: between particles and walls %.3f, wall contacts %.3f, "
                "contacts %.3f; heat out/in %.6f\n",
                row.T_K, porosity, k, k_contacts, reference, k / reference, cell("k_eff_W_per_mK"),
                zsb(cell("porosity"), row.T_K), cell("k_eff_W_per_mK") / zsb(cell("porosity"), row.T_K),
                cell("share_particle_radiation"), cell("share_wall_conduction"),
                cell("share_contact_conduction"), cell("heat_cold_W") / cell("heat_hot_W"));
    EXPECT_GE(k / reference, row.band.low) << row.T_K;
    EXPECT_LE(k / reference, row.band.high) << row.T_K;
    // Enclosed: what the hot wall gives the cold wall takes.
    EXPECT_LT(cell("balance_rel"), 1e-6) << row.T_K;
    if (row.T_K == 800.0) k_800 = k, zsb_800 = reference;
    if (row.T_K == 1200.0) k_1200 = k, zsb_1200 = reference;
  }
  // The trend: radiation's part of k_bulk (contacts subtracted) grows by less than (1200/800)^3 =
  // 3.375 with the shells in series (measured 2.80), ZSB's k_eff by 2.5 (glass in series too).
  const double trend = (k_1200 - k_contacts) / (k_800 - k_contacts);
  std::printf("[ valid    ] glass in vacuum, 1200 K against 800 K: tmdem (contacts subtracted) %.3f, "
              "ZSB %.3f, T^3 %.3f\n", trend, zsb_1200 / zsb_800, std::pow(1200.0 / 800.0, 3));
  EXPECT_GT(k_800, 20.0 * k_contacts);  // radiation carries the heat (measured 70 times contacts)
  EXPECT_NEAR(trend, 2.80, 0.1);
  EXPECT_NEAR(zsb_1200 / zsb_800, 2.50, 0.05);
}

}  // namespace
