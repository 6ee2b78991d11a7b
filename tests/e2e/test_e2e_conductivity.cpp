// End to end: `tmdem study conductivity` writes its CSV, refuses --pressures without a piston.
#include <gtest/gtest.h>

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
  EXPECT_NE(r.output.find("needs a piston"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/k.csv"));
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
