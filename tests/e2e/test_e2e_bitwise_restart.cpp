// End to end: a run stopped at a checkpoint and restarted from it writes the same result file,
// every dataset bit for bit, and the same summary (wall times aside), as the uninterrupted run:
// thermal-only with every integrator, a settled packing, a dynamic packing (docs/restart-and-files.md "Restart,
// interruption and files"). Both runs have the same checkpoint times, which are integration
// boundaries in both.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "E2eSupport.h"
#include "ResultComparison.h"

using namespace tmdem::e2e;
namespace fs = std::filesystem;

namespace {

// `example` run to `end_s` in one go, and in segments ending at each of `stops_s` (each
// restarted from the previous one's checkpoint), all with checkpoints every `interval_s`.
// `part_dir`, when given, receives the folder of the segmented run (its summary: s.json).
void expect_segments_equal_uninterrupted(const std::string& name, const std::string& example,
                                         double interval_s, const std::vector<double>& stops_s,
                                         double end_s, const std::string& settings = "",
                                         std::string* part_dir = nullptr) {
  const auto full = scratch_dir("bitwise_" + name + "_full");
  const auto part = scratch_dir("bitwise_" + name + "_part");
  if (part_dir) *part_dir = part;
  for (const auto& dir : {full, part})
    fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / example, dir + "/s.toml");
  const std::string common = "run s.toml --quiet -o out.h5 --set output.checkpoint_interval=" +
                             number(interval_s) + " " + settings;
  auto r = run_tmdem(common + " --summary s.json --set simulation.duration=" + number(end_s), full);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (std::size_t k = 0; k <= stops_s.size(); ++k) {
    const double until_s = k < stops_s.size() ? stops_s[k] : end_s;
    r = run_tmdem(common + (k > 0 ? " --restart out.checkpoint.h5" : "") +
                      (k == stops_s.size() ? " --summary s.json" : "") +
                      " --set simulation.duration=" + number(until_s),
                  part);
    ASSERT_EQ(r.exit_code, 0) << "segment " << k << ": " << r.output;
  }

  std::size_t compared = 0;
  const auto differences = result_differences(full + "/out.h5", part + "/out.h5", &compared);
  EXPECT_GE(compared, 12u);  // frames (time, position, velocity, temperature, ...), contacts, particles
  for (const auto& line : differences) ADD_FAILURE() << name << ": " << line;
  EXPECT_EQ(summary_without_wall_times(full + "/s.json"), summary_without_wall_times(part + "/s.json"))
      << name;

  H5::H5File restarted(part + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(restarted, "status"), "ok");
  std::vector<double> restart_times(stops_s.size(), -1.0);
  H5::Attribute attribute = restarted.openAttribute("restart_times");
  ASSERT_EQ(std::size_t(attribute.getSpace().getSimpleExtentNpoints()), stops_s.size());
  attribute.read(H5::PredType::NATIVE_DOUBLE, restart_times.data());
  EXPECT_EQ(restart_times, stops_s);
}

}  // namespace

// examples/lattice_constant.toml: 64 particles, 50 s, frames every 0.5 s; stopped at 20 s and
// at 40 s (two restarts in a row), with each integrator and linear solver.
class EndToEndBitwiseRestartLattice : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(EndToEndBitwiseRestartLattice, TwoRestartsEqualTheUninterruptedRun) {
  const auto [integrator, linear_solver] = GetParam();
  expect_segments_equal_uninterrupted(std::string(integrator) + "_" + linear_solver,
                                      "lattice_constant.toml", 20.0, {20.0, 40.0}, 50.0,
                                      std::string("--set thermal.integrator=") + integrator +
                                          " --set thermal.linear_solver=" + linear_solver);
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, EndToEndBitwiseRestartLattice,
                         ::testing::Values(std::pair{"cvode", "klu"}, std::pair{"cvode", "pcg"},
                                           std::pair{"cvode", "amg"}, std::pair{"ida", "klu"},
                                           std::pair{"ida", "pcg"}, std::pair{"ida", "amg"},
                                           std::pair{"explicit", "klu"}),
                         [](const auto& info) {
                           return std::string(info.param.first) + "_" + info.param.second;
                         });

// examples/paper_triangle.toml: settled before t = 0, then 200 s on the frozen graph.
TEST(EndToEndBitwiseRestart, PaperTriangleSettle) {
  expect_segments_equal_uninterrupted("triangle", "paper_triangle.toml", 100.0, {100.0}, 200.0);
}

// examples/poured_bed.toml: 80 particles poured, contacts changing every step; stopped at 0.2 s
// of 0.5 s (the restart needs the candidate table, the warm-start forces and the thermal
// network's pattern of that step), with the default contact solver, "nncg".
TEST(EndToEndBitwiseRestart, PouredBedDynamic) {
  expect_segments_equal_uninterrupted("poured_bed", "poured_bed.toml", 0.2, {0.2}, 0.5);
}

// The same with "nlgs", the default contact solver before "nncg" (which the test above runs).
TEST(EndToEndBitwiseRestart, PouredBedDynamicNlgs) {
  expect_segments_equal_uninterrupted("poured_bed_nlgs", "poured_bed.toml", 0.2, {0.2}, 0.5,
                                      "--set mechanics.solver=nlgs");
}

// The same with the accelerated contact solver, which carries its step-size estimate along.
TEST(EndToEndBitwiseRestart, PouredBedDynamicApgd) {
  expect_segments_equal_uninterrupted("poured_bed_apgd", "poured_bed.toml", 0.2, {0.2}, 0.5,
                                      "--set mechanics.solver=apgd");
}

// The tolerance schedule (mechanics.fall_tolerance, fall_speed): poured_bed's largest speed
// passes 0.05 m/s in its first steps and drops back below it at about 0.08 s, so the first
// segment ends while the particles fall (solved at fall_tolerance) and the second after the
// tolerance tightened; the checkpoint carries the schedule's phase and its counters.
TEST(EndToEndBitwiseRestart, PouredBedDynamicAcrossTheToleranceSwitch) {
  const std::string schedule = "--set mechanics.fall_tolerance=1e-4 --set mechanics.fall_speed=0.05";
  std::string part;
  expect_segments_equal_uninterrupted("poured_bed_schedule", "poured_bed.toml", 0.05, {0.05, 0.1},
                                      0.15, schedule, &part);
  const auto summary = read_summary(part + "/s.json");
  const auto& ts = summary.at("mechanics").at("tolerance_schedule");
  EXPECT_EQ(ts.at("fall_tolerance").get<double>(), 1e-4);
  EXPECT_EQ(ts.at("tolerance").get<double>(), 1e-5);  // the default
  ASSERT_TRUE(ts.at("tightened").get<bool>());
  const auto step = ts.at("tightened_step").get<std::int64_t>();
  EXPECT_GT(step, 50) << "the switch should come after the first restart";
  EXPECT_LE(step, 100) << "and before the second";
  EXPECT_DOUBLE_EQ(ts.at("tightened_time_s").get<double>(), double(step - 1) * 1e-3);
  EXPECT_GT(ts.at("fall_steps").get<std::int64_t>(), 0);
  EXPECT_LE(ts.at("fall_unconverged_steps").get<std::int64_t>(),
            summary.at("mechanics").at("unconverged_steps").get<std::int64_t>());
}

// examples/periodic_bed.toml: 60 spheres poured into a box periodic along x and z, contacts
// round the boundaries and particles wrapped as they cross; stopped at 0.1 s of 0.3 s. The
// periodic box is scene data: the checkpoint's wrapped positions and candidate table restart
// the same steps.
TEST(EndToEndBitwiseRestart, PeriodicBedDynamic) {
  expect_segments_equal_uninterrupted("periodic_bed", "periodic_bed.toml", 0.1, {0.1}, 0.3);
}
