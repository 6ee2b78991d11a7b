// A real peer: LIGGGHTS pours and settles 100 spheres with the input of docs/import-dem.md, and
// tmdem runs the scene of that page on its dumps (mechanics off, Hertz conductance of the
// imported forces). The floor carries the bed's weight (wall forces from each particle's
// balance), every pair contact has H = 2 k a of its force, and the energy balances. Skipped
// when `liggghts` is not installed (Debian package liggghts).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The text of the first block fenced ```LANGUAGE in docs/import-dem.md.
std::string fenced_block(const std::string& language) {
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/docs/import-dem.md");
  std::stringstream page;
  page << in.rdbuf();
  const std::string text = page.str(), open = "```" + language + "\n";
  const auto start = text.find(open);
  if (start == std::string::npos) return {};
  const auto begin = start + open.size();
  return text.substr(begin, text.find("```", begin) - begin);
}

}  // namespace

TEST(EndToEndLiggghts, PouredBedImportedWithItsForcesHeatsThroughHertzContacts) {
  if (std::system("command -v liggghts > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "liggghts is not installed (apt-get install liggghts)";
  const auto dir = scratch_dir("liggghts");
  const std::string input = fenced_block("liggghts"), scene = fenced_block("toml");
  ASSERT_FALSE(input.empty() || scene.empty()) << "docs/import-dem.md lost its blocks";
  write_file(dir + "/pour.in", input);
  write_file(dir + "/bed.toml", scene);
  ASSERT_EQ(std::system(("cd " + dir + " && liggghts -in pour.in -log log.liggghts > liggghts.out 2>&1").c_str()), 0)
      << "see " << dir << "/liggghts.out";
  const auto r = run_tmdem("run bed.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  H5::H5File f(dir + "/bed.h5", H5F_ACC_RDONLY);
  const auto [pair, offset, force, H] = read_contact_data(f);
  const auto mass = read_doubles(f, "/particles/mass");
  const auto radius = read_doubles(f, "/particles/radius");
  ASSERT_EQ(mass.size(), 100u);
  double weight_N = 0.0;
  for (const double m : mass) weight_N += m * 9.81;
  // Glass of the scene: E 6.3e10 Pa, nu 0.25, k 1 W/(m K).
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
  EXPECT_GT(pairs, 150);  // a settled bed: about 2 pair contacts per particle or more
  EXPECT_NEAR(floor_N, weight_N, 0.02 * weight_N);
  const auto s = read_summary(dir + "/s.json");
  EXPECT_GT(s["energy"]["boundary_heat_J"].get<double>(), 0.0);
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);
}
