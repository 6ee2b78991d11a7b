// End to end: `tmdem study conductivity` writes its CSV, refuses --pressures without a piston,
// and with one follows Hertz theory: k_eff ~ P^(1/3) on a lattice pressed by a piston.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

const std::string kLattice =
    thermal_scene()
        .add("generate", lattice({3, 4, 3}))
        .add("wall", floor_wall({{"temperature", 320.0}}))
        .add("wall", plane_wall({0.0, 0.008, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 300.0}}))
        .str();

TEST(E2eConductivity, WritesCsvWithKEff) {
  const auto dir = scratch_dir("conductivity_csv");
  write_file(dir + "/bed.toml", kLattice);
  const auto r = run_tmdem("study conductivity bed.toml --csv k.csv --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("k_eff = "), std::string::npos) << r.output;
  std::ifstream in(dir + "/k.csv");
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header.rfind("pressure_Pa,k_eff_W_per_mK,heat_hot_W,heat_cold_W,balance_rel,porosity,"
                         "coordination,length_m,area_m2,T_hot_K,T_cold_K,particles,contacts,"
                         "wall_contacts,floating_particles,share_contact_conduction",
                         0),
            0u)
      << header;
  // No piston: the pressure cell is empty; k_eff = H / d * 4 / 5 = 0.4 W/(m K).
  ASSERT_FALSE(row.empty());
  EXPECT_EQ(row[0], ',');
  const double k = std::stod(row.substr(1));
  EXPECT_NEAR(k, 0.4, 1e-12);
}

TEST(E2eConductivity, PressuresNeedAPiston) {
  const auto dir = scratch_dir("conductivity_piston");
  write_file(dir + "/bed.toml", kLattice);
  const auto r = run_tmdem("study conductivity bed.toml --pressures 1e3,1e4 --csv k.csv", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("needs exactly one wall with piston = true"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/k.csv"));
}

namespace {

// A 3 x 4 x 3 simple cubic steel lattice in a box (side walls x, z = 0 and 6 mm), hot floor,
// cold piston of 1 g resting on the top layer; no gravity, vacuum, Hertz contact conduction.
// Frictionless: with friction the side contacts could take part of the load (the statics of a
// lattice in a box is indeterminate), and the columns would not carry P A / 9 each.
std::string piston_lattice() {
  return SceneBuilder()
      .set("simulation.duration", 1.0)
      .add("material", steel({{"friction", 0.0}}))
      .set({{"effects.mechanics", "settle"}, {"mechanics.tolerance", 1e-10}})
      .add("generate", lattice({3, 4, 3}))
      .add("wall", floor_wall({{"temperature", 310.0}}))
      .add("wall", plane_wall({0.0, 0.008, 0.0}, {0.0, -1.0, 0.0},
                              {{"temperature", 290.0}, {"piston", true}, {"mass", 1e-3}}))
      .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
      .add("wall", plane_wall({0.006, 0.0, 0.0}, {-1.0, 0.0, 0.0}))
      .add("wall", plane_wall({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}))
      .add("wall", plane_wall({0.0, 0.0, 0.006}, {0.0, 0.0, -1.0}))
      .str();
}

std::vector<std::vector<double>> csv_numbers(const std::string& path, std::size_t columns) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::vector<double> row;
    std::string cell;
    while (row.size() < columns && std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

// Every column of the lattice carries the piston's force F = P A / 9 through its 5 contacts in
// series, and a Hertz conductance goes as F^(1/3): k_eff = c P^(1/3) exactly, whatever c.
TEST(E2eConductivity, PistonLoadedLatticeFollowsHertzOneThirdPowerLaw) {
  const auto dir = scratch_dir("conductivity_piston_lattice");
  write_file(dir + "/bed.toml", piston_lattice());
  const auto r = run_tmdem("study conductivity bed.toml --pressures 1e3,1e4,1e5 --csv k.csv --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = csv_numbers(dir + "/k.csv", 9);
  ASSERT_EQ(rows.size(), 3u);
  const double pressures[] = {1e3, 1e4, 1e5};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(rows[k][0], pressures[k]);
    // The piston stays on the top layer: L = 8 mm (rigid spheres).
    EXPECT_NEAR(rows[k][7], 0.008, 1e-9);
    EXPECT_EQ(rows[k][8], 3.6e-5);  // A from the side walls
  }
  for (std::size_t k = 1; k < 3; ++k) {
    const double exponent = std::log(rows[k][1] / rows[k - 1][1]) / std::log(10.0);
    EXPECT_NEAR(exponent, 1.0 / 3.0, 1e-4) << "between " << pressures[k - 1] << " and " << pressures[k] << " Pa";
  }
}

TEST(E2eConductivity, PressuresNeedMechanicsAndOnePiston) {
  const auto dir = scratch_dir("conductivity_piston_off");
  write_file(dir + "/bed.toml", piston_lattice());
  auto r = run_tmdem("study conductivity bed.toml --pressures 1e3 --set effects.mechanics=off --set thermal.conductance=constant", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("needs effects.mechanics = \"settle\""), std::string::npos) << r.output;
  r = run_tmdem("study conductivity bed.toml --pressures -5", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(E2eConductivity, SceneWithoutTwoIsothermalWallsIsExit2) {
  const auto dir = scratch_dir("conductivity_walls");
  write_file(dir + "/bed.toml", thermal_scene().add("generate", lattice({2, 2, 2})).add("wall", floor_wall()).str());
  const auto r = run_tmdem("study conductivity bed.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("exactly two walls with a temperature"), std::string::npos) << r.output;
}

// A lid above the bed (not touching it): k_eff = 0, and the command says why.
TEST(E2eConductivity, LidNotTouchingTheBedIsReported) {
  const auto dir = scratch_dir("conductivity_lid");
  write_file(dir + "/bed.toml",
             thermal_scene()
                 .add("generate", lattice({2, 2, 2}))
                 .add("wall", floor_wall({{"temperature", 320.0}}))
                 .add("wall", plane_wall({0.0, 0.01, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 300.0}}))
                 .str());
  const auto r = run_tmdem("study conductivity bed.toml", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the cold wall[1] touches no particle"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("k_eff = 0 W/(m K)"), std::string::npos) << r.output;
}

}  // namespace
