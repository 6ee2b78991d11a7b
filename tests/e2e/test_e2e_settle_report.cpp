// End to end: how a settle run reports its packing (issue 10 item 3). The summary's "settle"
// block, the final lines on stderr (largest penetration; a packing frozen before it came to
// rest), stalled_steps, and warnings that name the contact solver in use.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The last `count` non-empty lines of a program's output.
std::vector<std::string> last_lines(const std::string& text, std::size_t count) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  if (lines.size() > count) lines.erase(lines.begin(), lines.end() - std::ptrdiff_t(count));
  return lines;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

// Two touching steel spheres standing on the floor: at rest within a few steps.
std::string resting_column(const std::string& solver) {
  return steel_scene()
      .set({{"simulation.duration", 10.0},
            {"simulation.dimension", 3},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", "settle"},
            {"mechanics.solver", solver},
            {"mechanics.time_step", 1.0e-3}})
      .add("generate", column(2))
      .add("wall", floor_wall())
      .set(output("out.h5", 5.0))
      .str();
}

}  // namespace

TEST(EndToEndSettleReport, FallingSphereIsFrozenNotAtRestAndSaysSoInItsLastLines) {
  const auto dir = scratch_dir("settle_not_at_rest");
  // Free fall all along: after n = 10 steps of h = 1 ms the speed is n h g exactly.
  write_file(dir + "/s.toml", falling_sphere_scene());
  for (const std::string quiet : {"", " --quiet"}) {
    const auto r = run_tmdem("run s.toml --overwrite --summary s.json" + quiet, dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto s = read_summary(dir + "/s.json");
    ASSERT_TRUE(s.contains("settle")) << s.dump(2);
    EXPECT_FALSE(s["settle"]["at_rest"].get<bool>());
    EXPECT_EQ(s["settle"]["steps"].get<long>(), 10);
    EXPECT_EQ(s["mechanics"]["steps"].get<long>(), 10);
    EXPECT_NEAR(s["settle"]["time_s"].get<double>(), 0.01, 1e-15);
    EXPECT_NEAR(s["settle"]["max_speed_m_s"].get<double>(), 10 * 1.0e-3 * 9.81, 1e-12);
    EXPECT_EQ(s["mechanics"]["stalled_steps"].get<long>(), 0);
    const auto tail = last_lines(r.output, 3);
    EXPECT_TRUE(any_contains(tail, "frozen WITHOUT coming to rest")) << r.output;
    EXPECT_TRUE(any_contains(tail, "0.0981 m/s")) << r.output;
  }
}

TEST(EndToEndSettleReport, RestingColumnReportsAtRestAndItsLargestPenetration) {
  const auto dir = scratch_dir("settle_at_rest");
  write_file(dir + "/s.toml", resting_column("nlgs"));
  const auto r = run_tmdem("run s.toml --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_summary(dir + "/s.json");
  ASSERT_TRUE(s.contains("settle")) << s.dump(2);
  EXPECT_TRUE(s["settle"]["at_rest"].get<bool>());
  const long steps = s["settle"]["steps"].get<long>();
  EXPECT_GE(steps, 1);
  EXPECT_EQ(s["mechanics"]["steps"].get<long>(), steps);  // settle is all the mechanics here
  EXPECT_NEAR(s["settle"]["time_s"].get<double>(), double(steps) * 1.0e-3, 1e-12);
  EXPECT_LT(s["settle"]["max_speed_m_s"].get<double>(), 1.0e-4);  // settle_velocity default
  const auto tail = last_lines(r.output, 2);
  EXPECT_EQ(r.output.find("WITHOUT coming to rest"), std::string::npos) << r.output;
  // "mechanics: ... largest penetration <m> m (<p>% of the smallest radius)" among the last lines.
  ASSERT_TRUE(any_contains(tail, "largest penetration ")) << r.output;
  const std::string line = tail.back();
  const auto at = line.find("largest penetration ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double printed_m = std::stod(line.substr(at + 20));
  const double summary_m = s["mechanics"]["max_penetration_m"].get<double>();
  EXPECT_NEAR(printed_m, summary_m, 1e-5 * summary_m + 1e-300);
  EXPECT_NE(line.find("% of the smallest radius"), std::string::npos) << line;
}

TEST(EndToEndSettleReport, UnconvergedWarningsNameTheSolverInUse) {
  for (const std::string solver : {"nlgs", "apgd"}) {
    const auto dir = scratch_dir("settle_solver_" + solver);
    write_file(dir + "/s.toml", resting_column(solver));
    // Two iterations cannot reach 1e-14: every step is unconverged (from no forces: the static
    // warm start is the resting column's exact statics).
    const auto r = run_tmdem(
        "run s.toml --summary s.json --set mechanics.max_iterations=2 "
        "--set mechanics.tolerance=1e-14 --set mechanics.settle_time=0.005 "
        "--set mechanics.static_warm_start=false",
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto s = read_summary(dir + "/s.json");
    EXPECT_GT(s["mechanics"]["unconverged_steps"].get<long>(), 0) << solver;
    EXPECT_NE(r.output.find("contact solver " + solver + " did not converge"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("Gauss-Seidel"), std::string::npos) << r.output;
  }
}

TEST(EndToEndSettleReport, RestartedSettleRunKeepsItsSettleBlock) {
  const auto dir = scratch_dir("settle_restart");
  write_file(dir + "/s.toml", resting_column("nlgs"));
  auto r = run_tmdem("run s.toml --quiet --summary first.json --set output.checkpoint_interval=5",
                     dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("run s.toml --quiet --summary second.json --restart out.checkpoint.h5 "
                "--set output.checkpoint_interval=5 --set simulation.duration=20",
                dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto first = read_summary(dir + "/first.json"), second = read_summary(dir + "/second.json");
  ASSERT_TRUE(second.contains("settle")) << second.dump(2);
  EXPECT_EQ(second["settle"], first["settle"]);
}

// A deposit laid 1 mm above the floor wall (DepositSupport.h): `tmdem check` (stdout) and
// `tmdem run` (stderr, even with --quiet) warn naming the [[generate]] entry, the fall and
// the wall; the run then starts with the bed in free fall (5 steps: 5 h g, the floor 1 mm
// away is not reached).
TEST(EndToEndSettleReport, DepositAboveItsFloorIsWarnedOfByCheckAndRun) {
  const auto dir = scratch_dir("settle_lifted_deposit");
  write_file(dir + "/s.toml",
             steel_scene()
                 .set({{"simulation.duration", 0.01},
                       {"simulation.dimension", 3},
                       {"simulation.gravity", {0.0, -9.81, 0.0}},
                       {"effects.mechanics", "settle"},
                       {"mechanics.time_step", 1.0e-3},
                       {"mechanics.settle_time", 0.005}})
                 .add("generate", with(random_fill(30, "{ min = [0.0, 0.001, 0.0], max = [0.01, 0.03, 0.01] }",
                                                         {{"radius", 0.001}}),
                                       {{"kind", "deposit"}}))
                 .add("wall", floor_wall())
                 .set(output("out.h5", 0.01))
                 .str());
  const std::string warning = "warning: generate[0] (kind = \"deposit\")";
  auto r = run_tmdem("check s.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(warning), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("falls 0.001 m onto wall[0]"), std::string::npos) << r.output;
  r = run_tmdem("run s.toml --quiet --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(warning), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("falls 0.001 m onto wall[0]"), std::string::npos) << r.output;
  const auto s = read_summary(dir + "/s.json");
  EXPECT_NEAR(s["settle"]["max_speed_m_s"].get<double>(), 5 * 1.0e-3 * 9.81, 1e-9);
}
