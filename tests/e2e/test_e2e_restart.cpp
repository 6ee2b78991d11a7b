// End to end: a run stopped at a checkpoint and restarted with --restart ends where an
// uninterrupted run ends, and its result file holds the same frames.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {
const std::string kScene = thermal_scene()
                                 .set("simulation.duration", 20.0)
                                 .add("generate", lattice({3, 2, 2}))
                                 .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
                                 .add("wall", floor_wall({{"temperature", 350.0}}))
                                 .set(tolerances(1.0e-10))
                                 .set(output("out.h5", 2.0))
                                 .set("output.checkpoint_interval", 10.0);
}  // namespace

TEST(EndToEndRestart, RestartFromCheckpointMatchesUninterruptedRun) {
  const auto full = scratch_dir("restart_full");
  const auto part = scratch_dir("restart_part");
  write_file(full + "/s.toml", kScene);
  write_file(part + "/s.toml", kScene);
  ASSERT_EQ(run_tmdem("run s.toml --quiet --summary s.json", full).exit_code, 0);
  // Stop at t = 10 s (the checkpoint), then continue to 20 s from it.
  auto r = run_tmdem("run s.toml --quiet --set simulation.duration=10.0", part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(part + "/out.checkpoint.h5"));
  r = run_tmdem("run s.toml --quiet --restart out.checkpoint.h5 --summary s.json", part);
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
}
