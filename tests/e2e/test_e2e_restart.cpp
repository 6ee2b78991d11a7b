// End to end: a run stopped at a checkpoint and restarted with --restart ends where an
// uninterrupted run ends, and its result file holds the same frames.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>
#include <utility>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {
std::string restart_scene(double wall_temperature_K) {
  return thermal_scene()
      .set("simulation.duration", 20.0)
      .add("generate", lattice({3, 2, 2}))
      .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
      .add("wall", floor_wall({{"temperature", wall_temperature_K}}))
      .set(tolerances(1.0e-10))
      .set(output("out.h5", 2.0))
      .set("output.checkpoint_interval", 10.0);
}
const std::string kScene = restart_scene(350.0);

// Two folders with the scene: `full` run to its 20 s, `part` stopped at its checkpoint (10 s).
// Returns {full, part}, or empty names after a failed run.
std::pair<std::string, std::string> full_and_stopped_runs(const std::string& name) {
  const auto full = scratch_dir(name + "_full");
  const auto part = scratch_dir(name + "_part");
  write_file(full + "/s.toml", kScene);
  write_file(part + "/s.toml", kScene);
  auto r = run_tmdem("run s.toml --quiet --summary s.json", full);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("run s.toml --quiet --set simulation.duration=10.0", part);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (::testing::Test::HasFailure() || !std::filesystem::exists(part + "/out.checkpoint.h5")) return {};
  return {full, part};
}
}  // namespace

TEST(EndToEndRestart, RestartFromCheckpointMatchesUninterruptedRun) {
  // Stop at t = 10 s (the checkpoint), then continue to 20 s from it.
  const auto [full, part] = full_and_stopped_runs("restart");
  ASSERT_FALSE(part.empty());
  const auto r = run_tmdem("run s.toml --quiet --restart out.checkpoint.h5 --summary s.json", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  H5::H5File a(full + "/out.h5", H5F_ACC_RDONLY), b(part + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(b, "status"), "ok");
  const auto ta = read_doubles(a, "/frames/time"), tb = read_doubles(b, "/frames/time");
  ASSERT_EQ(ta, tb);
  const auto Ta = read_doubles(a, "/frames/temperature"), Tb = read_doubles(b, "/frames/temperature");
  ASSERT_EQ(Ta.size(), Tb.size());
  for (std::size_t i = 0; i < Ta.size(); ++i) EXPECT_NEAR(Ta[i], Tb[i], 1e-6) << i;
  const auto Qa = read_doubles(a, "/frames/boundary_heat"), Qb = read_doubles(b, "/frames/boundary_heat");
  for (std::size_t i = 0; i < Qa.size(); ++i) EXPECT_NEAR(Qa[i], Qb[i], 1e-8 + 1e-6 * std::abs(Qa[i]));
  EXPECT_EQ(read_ints(a, "/frames/contact_offset"), read_ints(b, "/frames/contact_offset"));
  const auto s = read_summary(part + "/s.json");
  EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8);

  // The metadata tells the truth: the scene as last run (its longer duration) and the segment.
  const toml::table scene = toml::parse(read_string_attribute(b, "scene"));
  EXPECT_EQ(scene["simulation"]["duration"].value<double>(), 20.0);
  EXPECT_EQ(toml::parse(read_string_attribute(a, "scene")), scene);
  EXPECT_FALSE(a.attrExists("restart_times"));
  ASSERT_TRUE(b.attrExists("restart_times"));
  H5::Attribute restarts = b.openAttribute("restart_times");
  ASSERT_EQ(restarts.getSpace().getSimpleExtentNpoints(), 1);
  double restart_time_s = 0.0;
  restarts.read(H5::PredType::NATIVE_DOUBLE, &restart_time_s);
  EXPECT_EQ(restart_time_s, 10.0);
}

// output.* may differ on a restart: -o naming a result that does not exist yet continues a copy
// of the checkpoint's result there (bit for bit the uninterrupted run) and leaves the original
// as it was.
TEST(EndToEndRestart, RestartIntoAnotherFileContinuesACopyAndKeepsTheOriginal) {
  const auto [full, part] = full_and_stopped_runs("restart_other");
  ASSERT_FALSE(part.empty());
  const auto r = run_tmdem("run s.toml --quiet -o other.h5 --restart out.checkpoint.h5", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  H5::H5File a(full + "/out.h5", H5F_ACC_RDONLY), b(part + "/other.h5", H5F_ACC_RDONLY),
      original(part + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_doubles(a, "/frames/time"), read_doubles(b, "/frames/time"));
  EXPECT_EQ(read_doubles(a, "/frames/temperature"), read_doubles(b, "/frames/temperature"));
  EXPECT_EQ(read_string_attribute(b, "status"), "ok");
  EXPECT_TRUE(b.attrExists("restart_times"));
  // The original still ends at the checkpoint, never restarted.
  EXPECT_EQ(read_doubles(original, "/frames/time").back(), 10.0);
  EXPECT_FALSE(original.attrExists("restart_times"));
}

namespace {
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

TEST(EndToEndRestart, RestartWithAnotherConductanceIsRefusedAndChangesNoByte) {
  const auto part = scratch_dir("restart_changed");
  write_file(part + "/s.toml", kScene);
  auto r = run_tmdem("run s.toml --quiet --set simulation.duration=10.0", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> files = {"out.h5", "out.xdmf", "out.checkpoint.h5"};
  std::vector<std::string> before;
  for (const auto& f : files) before.push_back(file_bytes(part + "/" + f));

  r = run_tmdem("run s.toml --quiet --restart out.checkpoint.h5 --summary s.json "
                "--set thermal.constant_conductance=1.0", part);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("thermal.constant_conductance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checkpoint 0.001, now 1.0"), std::string::npos) << r.output;
  for (std::size_t k = 0; k < files.size(); ++k)
    EXPECT_TRUE(file_bytes(part + "/" + files[k]) == before[k]) << files[k] << " changed";
  EXPECT_FALSE(std::filesystem::exists(part + "/s.json"));

  // The same scene edited in the file (not by --set) is refused the same way.
  write_file(part + "/s.toml", restart_scene(351.0));
  r = run_tmdem("run s.toml --quiet --restart out.checkpoint.h5", part);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("wall[0].temperature"), std::string::npos) << r.output;
  for (std::size_t k = 0; k < files.size(); ++k)
    EXPECT_TRUE(file_bytes(part + "/" + files[k]) == before[k]) << files[k] << " changed";
}
