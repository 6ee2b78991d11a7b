// End to end with [periodic]: `study conductivity` on bulk lattices between two walls with no
// side walls (a simple cubic lattice under given contact forces: the Hertz chains of its columns
// over the periods; a body-centred lattice: the layered network, and without its periodic
// neighbours another number); a pair pushed across the boundary keeps its contact and its heat,
// the thermal energy conserved; a period too short for the fall is warned of and stops the run;
// a bed poured into an x-z periodic box settles inside it.
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The first data row of a study CSV, as numbers (the pressure cell may be empty: NaN).
std::vector<double> first_csv_row(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<double> row;
  std::istringstream cells(line);
  std::string cell;
  while (std::getline(cells, cell, ',')) row.push_back(cell.empty() ? NAN : std::stod(cell));
  return row;
}

// CSV columns of `study conductivity` (test_e2e_conductivity.cpp checks the header).
constexpr std::size_t kKEff = 1, kPorosity = 5, kLength = 7, kArea = 8;

// Hertz contact radius of steel (E 2.1e11 Pa, nu 0.3) on steel, m: R* = R_i R_j / (R_i + R_j).
double steel_hertz_radius_m(double force_N, double reduced_radius_m) {
  const double E_star = 2.1e11 / (2.0 * (1.0 - 0.3 * 0.3));
  return std::cbrt(3.0 * force_N * reduced_radius_m / (4.0 * E_star));
}

}  // namespace

// A simple cubic steel lattice, 3 x 3 columns of 4 touching spheres (radius 1 mm, spacing s =
// 2 mm), periodic along x and z with periods of 3 s (neighbouring columns touch round the
// boundaries), between a hot floor and a cold top wall; no side walls, mechanics off, the
// contact forces given: an [[import]] of LAMMPS dumps whose pair forces load column c with
// F_c = (c + 1) 10 mN, the walls taking each end sphere's balance. (A piston on rigid columns
// would leave their shares undetermined: the solver spreads them by about 1%.) Column c carries
// F_c through two wall contacts (R* = r) and three sphere contacts (R* = r/2) in series, Hertz
// H = 2 k a each (k = 50 W/(m K)), and the columns work in parallel:
//   k_eff = Q L / (A dT) = sum_c G_c L / (9 s^2),  1/G_c = 2/H_wall(F_c) + 3/H_pair(F_c),  L = 8 mm.
TEST(E2ePeriodic, LatticeIsTheHertzChainsOfItsColumnsOverThePeriods) {
  const auto dir = scratch_dir("periodic_lattice");
  const double s = 0.002, r_m = 0.001, period = 3.0 * s;
  std::string atoms, entries;
  int id = 1, pairs = 0;
  for (int c = 0; c < 9; ++c) {
    const double x = (0.5 + c % 3) * s, z = (0.5 + c / 3) * s, F = 0.01 * (c + 1);
    for (int level = 0; level < 4; ++level, ++id) {
      atoms += std::to_string(id) + " 1 " + std::to_string(x) + " " + std::to_string((0.5 + level) * s) +
               " " + std::to_string(z) + " 0.001\n";
      if (level > 0) {
        entries += std::to_string(id - 1) + " " + std::to_string(id) + " " + std::to_string(F) + "\n";
        ++pairs;
      }
    }
  }
  write_file(dir + "/bed.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n36\nITEM: BOX BOUNDS pp ff pp\n"
                                "0 0.006\n0 0.008\n0 0.006\nITEM: ATOMS id type x y z radius\n" + atoms);
  write_file(dir + "/pairs.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n" + std::to_string(pairs) +
                                  "\nITEM: BOX BOUNDS pp ff pp\n0 0.006\n0 0.008\n0 0.006\n"
                                  "ITEM: ENTRIES id1 id2 fn\n" + entries);
  write_file(dir + "/bed.toml",
             steel_scene()
                 .set("effects.mechanics", "off")
                 .set({{"periodic.x", {0.0, period}}, {"periodic.z", {0.0, period}}})
                 .add("import", {{"file", "bed.dump"}, {"material", "steel"}, {"contacts", "pairs.dump"}})
                 .add("wall", floor_wall({{"temperature", 310.0}}))
                 .add("wall", plane_wall({0.0, 0.008, 0.0}, {0.0, -1.0, 0.0}, {{"temperature", 290.0}}))
                 .str());
  const auto r = run_tmdem("study conductivity bed.toml --csv k.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("periodic along x, z"), std::string::npos) << r.output;
  const auto row = first_csv_row(dir + "/k.csv");
  ASSERT_GT(row.size(), kArea);
  EXPECT_NEAR(row[kArea], period * period, 1e-18);  // the periods
  EXPECT_NEAR(row[kLength], 0.008, 1e-15);
  // 36 spheres in A L = 36 s^3: 1 - pi/6.
  EXPECT_NEAR(row[kPorosity], 1.0 - std::numbers::pi / 6.0, 1e-12);
  double G = 0.0;
  for (int c = 0; c < 9; ++c) {
    const double F = 0.01 * (c + 1), k = 50.0;
    const double H_wall = 2.0 * k * steel_hertz_radius_m(F, r_m);
    const double H_pair = 2.0 * k * steel_hertz_radius_m(F, r_m / 2.0);
    G += 1.0 / (2.0 / H_wall + 3.0 / H_pair);
  }
  const double expected = G * 0.008 / (period * period);
  EXPECT_NEAR(row[kKEff], expected, 1e-10 * expected) << "measured " << row[kKEff];
}

// A body-centred cubic lattice (cell a = 2 d / sqrt 3, so that each sphere touches its 8
// diagonal neighbours only): 2 x 2 cells across, four layers (corner, centre, corner, centre),
// mechanics off, a constant conductance H per contact, periodic along x and z with periods of
// 2a. Each layer is isothermal, each layer interface holds 4 x 4 contacts, each wall touches 4
// spheres: 1/G = 2/(4 H) + 3/(16 H), and k_eff = G L / (2a)^2 with L = d + 3a/2. Without
// [periodic] the boundary spheres miss their neighbours round the boundary (and A is the
// particles' extent): another k_eff.
TEST(E2ePeriodic, BodyCentredLatticeNeedsItsNeighboursRoundTheBoundary) {
  const auto dir = scratch_dir("periodic_bcc");
  const double d = 0.002, a = 2.0 * d / std::sqrt(3.0), H = 1e-3;
  auto bcc = [&](bool periodic) {
    auto scene = thermal_scene()
                     .add("generate", lattice({2, 2, 2}, {{"spacing", a}}))
                     .add("generate", lattice({2, 2, 2}, {{"spacing", a},
                                                          {"origin", {0.001 + a / 2, 0.001 + a / 2,
                                                                      0.001 + a / 2}}}))
                     .add("wall", floor_wall({{"temperature", 320.0}}))
                     .add("wall", plane_wall({0.0, d + 1.5 * a, 0.0}, {0.0, -1.0, 0.0},
                                             {{"temperature", 300.0}}));
    if (periodic) scene.set({{"periodic.x", {0.0, 2 * a}}, {"periodic.z", {0.0, 2 * a}}});
    return scene.str();
  };
  write_file(dir + "/periodic.toml", bcc(true));
  write_file(dir + "/open.toml", bcc(false));
  auto r = run_tmdem("study conductivity periodic.toml --csv periodic.csv --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("study conductivity open.toml --csv open.csv --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto periodic = first_csv_row(dir + "/periodic.csv");
  const auto open = first_csv_row(dir + "/open.csv");
  ASSERT_GT(periodic.size(), kArea);
  ASSERT_GT(open.size(), kArea);
  const double G = 1.0 / (2.0 / (4.0 * H) + 3.0 / (16.0 * H));
  const double L = d + 1.5 * a, A = 4.0 * a * a;
  EXPECT_NEAR(periodic[kArea], A, 1e-15);
  EXPECT_NEAR(periodic[kLength], L, 1e-15);
  EXPECT_NEAR(periodic[kKEff], G * L / A, 1e-9 * G * L / A);
  // The open lattice: 9 contacts per interface instead of 16, and A = (1.5 a + d)^2.
  EXPECT_NEAR(open[kArea], std::pow(1.5 * a + d, 2), 1e-15);
  EXPECT_LT(open[kKEff], 0.8 * periodic[kKEff]);
}

// Gravity tilted by 0.1 rad along x over an adiabatic floor: sphere 0 (frictionless, 350 K)
// slides and pushes sphere 1 (steel, 300 K), which rolls; both cross the x boundary within
// 0.15 s (test_periodic_steps.cpp has the force). Their contact carries Hertz conduction all the
// way: every frame after the first lists it, the two temperatures close in, and nothing else
// exchanges heat, so sum C T stays what it was to round-off.
TEST(E2ePeriodic, APairCrossingTheBoundaryKeepsItsContactAndItsHeat) {
  const auto dir = scratch_dir("periodic_crossing");
  write_file(dir + "/slope.toml",
             SceneBuilder()
                 .set({{"simulation.duration", 0.15},
                       {"simulation.gravity", {9.81 * std::sin(0.1), -9.81 * std::cos(0.1), 0.0}},
                       {"effects.mechanics", "dynamic"},
                       {"mechanics.time_step", 1e-4},
                       {"mechanics.tolerance", 1e-10},
                       {"output.interval", 0.01}})
                 .set({{"periodic.x", {0.0, 0.01}}, {"periodic.z", {0.0, 0.01}}})
                 .add("material", steel({{"friction", 0.5}}))
                 .add("material", steel({{"name", "slick"}, {"friction", 0.0}}))
                 .add("particle", particle({0.006, 0.001, 0.005},
                                           {{"material", "slick"}, {"temperature", 350.0}}))
                 .add("particle", particle({0.008, 0.001, 0.005}, {{"temperature", 300.0}}))
                 .add("wall", floor_wall())
                 .str());
  const auto r = run_tmdem("run slope.toml -o slope.h5 --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File file(dir + "/slope.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto x = read_doubles(file, "/frames/position", &dims);
  const auto T = read_doubles(file, "/frames/temperature");
  const auto energy = read_doubles(file, "/frames/thermal_energy");
  const auto contacts = read_contact_data(file);
  const std::size_t frames = dims[0];
  ASSERT_GE(frames, 15u);
  int wraps[2] = {0, 0};
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t p = 0; p < 2; ++p) {
      const double xp = x[(f * 2 + p) * 3];
      EXPECT_GE(xp, 0.0);
      EXPECT_LT(xp, 0.01);
      if (f > 0) wraps[p] += xp < x[((f - 1) * 2 + p) * 3];
    }
    EXPECT_NEAR(energy[f], energy[0], 1e-12 * energy[0]) << "frame " << f;
    if (f == 0) continue;
    bool pair = false;
    for (long long c = contacts.offset[f]; c < contacts.offset[f + 1]; ++c)
      pair = pair || (contacts.pair[2 * c] == 0 && contacts.pair[2 * c + 1] == 1 &&
                      contacts.conductance_W_per_K[std::size_t(c)] > 0.0);
    EXPECT_TRUE(pair) << "frame " << f << ": the pair's contact is missing";
    EXPECT_LT(T[2 * f], T[2 * (f - 1)]) << "frame " << f;          // the hot one cools
    EXPECT_GT(T[2 * f + 1], T[2 * (f - 1) + 1]) << "frame " << f;  // the cold one warms
  }
  EXPECT_EQ(wraps[0], 1);
  EXPECT_EQ(wraps[1], 1);
}

// Only the motion across the periods is held to them (mechanics/detection/ContactDetector.h).
// Poured from 30 mm into 8 mm periods at the default 1 ms step, a sphere lands at about
// 0.78 m/s, along y, the walled axis: `tmdem check` does not warn and the run settles (it
// stopped when every axis was held to the periods). With gravity tilted 72 degrees towards x,
// a periodic axis, the spheres fall and then slide across the periods ever faster: the
// detector needs the look-aheads across them of two spheres together to fit in 8 / 2 - 2 = 2
// mm. `tmdem check` warns; the run halves its steps as the spheres speed up (down to 1/16 of
// the time step), then stops with an error naming both lengths rather than miss contacts.
// With gravity along y and 8 or 10 mm periods, neither.
TEST(E2ePeriodic, APeriodTooShortForTheFallIsWarnedOfAndStopsTheRun) {
  const auto dir = scratch_dir("periodic_short");
  auto pour = [](double period, double height, double gravity_x) {
    return SceneBuilder()
        .set({{"simulation.duration", 0.001},
              {"simulation.gravity", {gravity_x, -9.81, 0.0}},
              {"effects.mechanics", "settle"},
              {"mechanics.rest_test", "velocity"}})  // wait for every sphere to land
        .set({{"periodic.x", {0.0, period}}, {"periodic.z", {0.0, period}}})
        .add("material", glass({{"friction", 0.3}}))
        .add("generate", random_fill(40, "{ min = [0.0, 0.0, 0.0], max = [" + std::to_string(period) +
                                             ", " + std::to_string(height) + ", " +
                                             std::to_string(period) + "] }",
                                     {{"radii", {0.0008, 0.001}}, {"fractions", {0.5, 0.5}}, {"material", "glass"}}))
        .add("wall", floor_wall({{"material", "glass"}}))
        .str();
  };
  write_file(dir + "/across.toml", pour(0.008, 0.03, -30.0));
  write_file(dir + "/short.toml", pour(0.008, 0.03, 0.0));
  write_file(dir + "/wide.toml", pour(0.01, 0.02, 0.0));
  auto r = run_tmdem("check across.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("periodic: x [0, 0.008) m, z [0, 0.008) m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("more than the periods leave (0.002 m"), std::string::npos) << r.output;
  r = run_tmdem("run across.toml -o across.h5 --quiet", dir);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("a periodic period is too short for the contact reach"), std::string::npos)
      << r.output;
  // It says when: within the settle, not at set-up.
  EXPECT_NE(r.output.find("settling stopped at mechanics step "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("setting up"), std::string::npos) << r.output;
  for (const std::string name : {"short", "wide"}) {
    r = run_tmdem("check " + name + ".toml", dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("more than the periods leave"), std::string::npos) << r.output;
    r = run_tmdem("run " + name + ".toml -o " + name + ".h5 --quiet", dir);
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.output;
  }
}

// 150 glass spheres (radii 0.8 and 1 mm) poured into a box periodic along x and z (10 mm periods)
// onto a floor: they settle, every centre in the box, overlaps within twice the slop (1e-4 of
// the smallest radius), and contacts round the boundaries carry load.
TEST(E2ePeriodic, PouredBedSettlesInsideThePeriodicBox) {
  const auto dir = scratch_dir("periodic_pour");
  write_file(dir + "/pour.toml",
             SceneBuilder()
                 .set({{"simulation.duration", 0.001},
                       {"simulation.gravity", {0.0, -9.81, 0.0}},
                       {"effects.mechanics", "settle"}})
                 .set({{"periodic.x", {0.0, 0.01}}, {"periodic.z", {0.0, 0.01}}})
                 .add("material", glass({{"friction", 0.3}, {"rolling_friction", 0.1}}))
                 .add("generate", random_fill(150, "{ min = [0.0, 0.0, 0.0], max = [0.01, 0.02, 0.01] }",
                                              {{"radii", {0.0008, 0.001}},
                                               {"fractions", {0.5, 0.5}},
                                               {"material", "glass"}}))
                 .add("wall", floor_wall({{"material", "glass"}}))
                 .str());
  const auto r = run_tmdem("run pour.toml -o pour.h5 --summary pour.json --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = read_summary(dir + "/pour.json");
  EXPECT_TRUE(summary["settle"]["at_rest"].get<bool>()) << summary.dump();
  EXPECT_LE(summary["mechanics"]["max_penetration_m"].get<double>(), 2e-4 * 0.0008 * (1 + 1e-6));
  H5::H5File file(dir + "/pour.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto x = read_doubles(file, "/frames/position", &dims);
  const auto radius = read_doubles(file, "/particles/radius");
  ASSERT_EQ(dims[1], 150u);
  for (std::size_t i = 0; i < 150; ++i) {
    for (int a : {0, 2}) {
      EXPECT_GE(x[3 * i + a], 0.0) << "particle " << i;
      EXPECT_LT(x[3 * i + a], 0.01) << "particle " << i;
    }
    EXPECT_GE(x[3 * i + 1], radius[i] - 2e-4 * 0.0008) << "particle " << i;  // on the floor
  }
  const auto contacts = read_contact_data(file);
  std::size_t across = 0;
  for (long long c = contacts.offset[0]; c < contacts.offset[1]; ++c) {
    const long long i = contacts.pair[2 * c], j = contacts.pair[2 * c + 1];
    if (j < 0 || !(contacts.normal_force_N[std::size_t(c)] > 0.0)) continue;
    across += std::abs(x[3 * i] - x[3 * j]) > 0.005 || std::abs(x[3 * i + 2] - x[3 * j + 2]) > 0.005;
  }
  EXPECT_GT(across, 5u);
}
