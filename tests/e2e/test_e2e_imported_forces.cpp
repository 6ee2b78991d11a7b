// End to end without mechanics: a column of three steel spheres on a hot floor is imported from
// a LIGGGHTS particle dump with the local dump of its pair forces (the weights above each
// contact, written by hand). The run's Hertz conductances are 2 k a of those forces, the floor
// carries the column's weight (from the bottom sphere's balance), and heat flows in with the
// energy balanced. A malformed local dump stops the run with exit code 2 naming FILE:LINE.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

constexpr double kRadius = 1e-3, kG = 9.81, kDensity = 7800.0, kE = 2.1e11, kNu = 0.3, kK = 50.0;

std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The column x = z = 0, centres at y = 1, 3, 5 mm, ids 11 (bottom), 12, 13; rows unordered.
const std::string kParticles =
    "ITEM: TIMESTEP\n2000\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n-0.01 0.01\n0 "
    "0.01\n-0.01 0.01\nITEM: ATOMS id type x y z radius\n"
    "13 1 0 0.005 0 0.001\n11 1 0 0.001 0 0.001\n12 1 0 0.003 0 0.001\n";

// `compute pc all pair/gran/local pos id force` + `dump local`: positions of both, id1 id2 and
// the periodic flag, the force on the first (here with a tangential x part, which is dropped).
std::string pair_forces(const std::string& last_entry) {
  const double weight_N = kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kG;
  std::string out = "ITEM: TIMESTEP\n2000\nITEM: NUMBER OF ENTRIES\n2\nITEM: BOX BOUNDS ff ff ff\n"
                    "-0.01 0.01\n0 0.01\n-0.01 0.01\nITEM: ENTRIES";
  for (int k = 1; k <= 12; ++k) out += " c_pc[" + std::to_string(k) + "]";
  out += "\n0 0.003 0 0 0.001 0 12 11 0 1e-6 " + exact(2.0 * weight_N) + " 0\n";
  out += last_entry.empty() ? "0 0.003 0 0 0.005 0 12 13 0 0 " + exact(-weight_N) + " 0\n" : last_entry;
  return out;
}

// with_forces false: the same import without its contacts.
SceneBuilder column_scene(bool with_forces = true) {
  TomlKeys import{{"file", "column.dump"}, {"material", "steel"}};
  if (with_forces)
    import = with(import, {{"contacts", "pairs.dump"},
                           {"contact_columns",
                            raw("{ id1 = \"c_pc[7]\", id2 = \"c_pc[8]\", force = [\"c_pc[10]\", "
                                "\"c_pc[11]\", \"c_pc[12]\"] }")}});
  return steel_scene()
      .set({{"simulation.duration", 50.0},
            {"simulation.gravity", {0.0, -kG, 0.0}},
            {"effects.mechanics", "off"}})
      .add("import", import)
      .add("wall", floor_wall({{"temperature", 373.15}}))
      .set(tolerances(1.0e-10))
      .set(output("column.h5", 10.0));
}

// A fresh folder with the column's particle dump, its pair forces and its scene column.toml.
std::string column_folder(const std::string& name, const std::string& last_entry) {
  const auto dir = scratch_dir(name);
  write_file(dir + "/column.dump", kParticles);
  write_file(dir + "/pairs.dump", pair_forces(last_entry));
  write_file(dir + "/column.toml", column_scene());
  return dir;
}

}  // namespace

TEST(EndToEndImportedForces, HertzConductancesOfTheDumpsForcesAndTheFloorCarriesTheWeight) {
  const auto dir = column_folder("imported_forces", "");
  const auto r = run_tmdem("run column.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  H5::H5File f(dir + "/column.h5", H5F_ACC_RDONLY);
  const auto [pair, offset, force, H] = read_contact_data(f);
  const double W = kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kG;
  const double E_star = kE / (2.0 * (1.0 - kNu * kNu));
  // H = 2 k a, a = (3 F R* / (4 E*))^(1/3): R* = r/2 between spheres, r against the wall.
  const auto hertz = [&](double F, double R_star) { return 2.0 * kK * std::cbrt(3.0 * F * R_star / (4.0 * E_star)); };
  ASSERT_EQ(offset[1] - offset[0], 3);
  const std::vector<long long> pairs{0, 1, 1, 2, 0, -1};  // scene ids: 11 -> 0, 12 -> 1, 13 -> 2
  const std::vector<double> forces{2.0 * W, W, 3.0 * W};
  const std::vector<double> conductances{hertz(2.0 * W, kRadius / 2), hertz(W, kRadius / 2),
                                         hertz(3.0 * W, kRadius)};
  for (long long c = 0; c < 3; ++c) {
    EXPECT_EQ(pair[2 * c], pairs[2 * c]);
    EXPECT_EQ(pair[2 * c + 1], pairs[2 * c + 1]);
    EXPECT_NEAR(force[c], forces[c], 1e-12 * forces[c]) << "contact " << c;
    EXPECT_NEAR(H[c], conductances[c], 1e-12 * conductances[c]) << "contact " << c;
  }
  // Heat flows in from the floor, and every joule of it is in the spheres.
  const auto T = read_doubles(f, "/frames/temperature");
  EXPECT_GT(T[T.size() - 3], 293.15 + 1.0);
  EXPECT_GT(T.back(), 293.15);
  const auto s = read_summary(dir + "/s.json");
  EXPECT_GT(s["energy"]["boundary_heat_J"].get<double>(), 0.0);
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
}

TEST(EndToEndImportedForces, MalformedLocalDumpStopsTheRunNamingFileAndLine) {
  const auto dir = column_folder("imported_forces_bad", "0 0.003 0 0 0.005 0 12 14 0 0 -1e-3 0\n");
  const auto r = run_tmdem("run column.toml --quiet", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("import[0].contacts: pairs.dump:11: particle id 14 is not in column.dump"),
            std::string::npos) << r.output;
  // Hertz without the forces is refused as before, now naming the way out.
  write_file(dir + "/plain.toml", column_scene(false));
  const auto plain = run_tmdem("run plain.toml --quiet", dir);
  EXPECT_EQ(plain.exit_code, 2);
  EXPECT_NE(plain.output.find("import the packing with its forces ([[import]] contacts)"),
            std::string::npos) << plain.output;
}
