#pragma once
// What the two real-peer tests (LIGGGHTS, LAMMPS) share: the fenced blocks of
// docs/import-dem.md they run, and the checks on the heated bed tmdem makes of the peer's dumps
// (mechanics off, Hertz conductance of the imported forces): the floor carries the bed's weight
// (wall forces from each particle's balance), every pair contact has H = 2 k a of its force, and
// the energy balances.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "E2eSupport.h"

namespace tmdem::e2e {

// The texts of the blocks fenced ```LANGUAGE in docs/import-dem.md, in page order.
inline std::vector<std::string> import_page_blocks(const std::string& language) {
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/docs/import-dem.md");
  std::stringstream page;
  page << in.rdbuf();
  const std::string text = page.str(), open = "```" + language + "\n";
  std::vector<std::string> blocks;
  for (auto start = text.find(open); start != std::string::npos; start = text.find(open, start + 1)) {
    const auto begin = start + open.size();
    blocks.push_back(text.substr(begin, text.find("```", begin) - begin));
  }
  return blocks;
}

// The glass of the page's scene: E 6.3e10 Pa, nu 0.25, k 1 W/(m K); 100 particles.
inline void expect_heated_bed(const std::string& dir, long long min_pairs, double floor_tolerance) {
  H5::H5File f(dir + "/bed.h5", H5F_ACC_RDONLY);
  const auto [pair, offset, force, H] = read_contact_data(f);
  const auto mass = read_doubles(f, "/particles/mass");
  const auto radius = read_doubles(f, "/particles/radius");
  ASSERT_EQ(mass.size(), 100u);
  double weight_N = 0.0;
  for (const double m : mass) weight_N += m * 9.81;
  const double E_star = 6.3e10 / (2.0 * (1.0 - 0.25 * 0.25));
  double floor_N = 0.0;
  long long pairs = 0;
  for (long long c = offset[0]; c < offset[1]; ++c) {
    const auto i = pair[2 * c], j = pair[2 * c + 1];
    if (j == -1) floor_N += force[c];
    if (j < 0) continue;
    ++pairs;
    const double R_star = radius[i] * radius[j] / (radius[i] + radius[j]);
    const double a = std::cbrt(3.0 * force[c] * R_star / (4.0 * E_star));
    EXPECT_GT(force[c], 0.0) << "contact " << c;
    EXPECT_NEAR(H[c], 2.0 * 1.0 * a, 1e-12 * a) << "contact " << c;
  }
  EXPECT_GT(pairs, min_pairs);  // a settled bed: about 2 pair contacts per particle or more
  EXPECT_NEAR(floor_N, weight_N, floor_tolerance * weight_N);
  const auto s = read_summary(dir + "/s.json");
  EXPECT_GT(s["energy"]["boundary_heat_J"].get<double>(), 0.0);
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
}

}  // namespace tmdem::e2e
