// A settle stopped after any step and resumed from a settle checkpoint (SettleProgress.h, the
// integrator's MechanicsState, both through the checkpoint file) ends exactly as the settle that
// never stopped: at the same step, by the same test, with the same packing bit for bit. The
// rest test's window is part of it: a settle resumed without it could not come to rest until the
// window had filled again.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/output/Checkpoint.h"
#include "coupling/run/RestartState.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;
namespace fs = std::filesystem;

// 40 steel spheres (1 mm) dropped into a 12 x 12 mm box: they come to rest by the network test well
// within settle_time.
Scene dropped_spheres(const std::string& rest_test) {
  const auto text = steel_scene()
                        .set({{"effects.mechanics", "settle"},
                              {"simulation.gravity", {0.0, -9.81, 0.0}},
                              {"mechanics.settle_time", 1.0},
                              {"mechanics.rest_test", rest_test},
                              {"mechanics.settle_velocity", 1.0e-3},
                              {"thermal.conductance", "constant"},
                              {"thermal.constant_conductance", 1.0e-3}})
                        .add("generate", random_fill(40, "{ min = [0.0, 0.0, 0.0], max = [0.012, 0.008, 0.012] }",
                                                     {{"radius", 0.001}}))
                        .add("wall", floor_wall())
                        .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
                        .add("wall", plane_wall({0.012, 0.0, 0.0}, {-1.0, 0.0, 0.0}))
                        .add("wall", plane_wall({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}))
                        .add("wall", plane_wall({0.0, 0.0, 0.012}, {0.0, 0.0, -1.0}))
                        .str();
  return load_scene_text(text, "scene.toml");
}

struct Settled {
  SettleSummary summary;
  mechanics::MechanicsState state;
};

// The whole settle in one go.
Settled settle_whole(const Scene& scene) {
  auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
  std::ostringstream sink;
  ProgressReporter progress(sink, true, false);
  SettleProgress where;
  Settled out{settle_packing(*nscd, scene, progress, nullptr, &where), {}};
  EXPECT_TRUE(where.finished);
  out.state = nscd->save_state();
  return out;
}

// Stopped after `stop_after` steps, written to a settle checkpoint, read back into an
// integrator built anew from the scene, and resumed to the end.
Settled settle_in_two(const Scene& scene, int stop_after, const std::string& path) {
  std::ostringstream sink;
  ProgressReporter progress(sink, true, false);
  {
    auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
    SettleProgress where;
    int steps = 0;
    const SettleSummary first =
        settle_packing(*nscd, scene, progress, [&] { return ++steps >= stop_after; }, &where);
    EXPECT_FALSE(first.at_rest);
    EXPECT_FALSE(where.finished);
    EXPECT_EQ(where.steps, stop_after);
    EXPECT_EQ(first.steps, stop_after);
    CheckpointState cs;
    store_mechanics_state(nscd->save_state(), cs);
    cs.temperature_K.assign(scene.particles.size(), 300.0);
    store_settle_progress(where, cs);
    write_checkpoint(path, cs);
  }
  const CheckpointState read = read_checkpoint(path);
  EXPECT_TRUE(read.settling);
  auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
  nscd->restore_state(mechanics_state_of(read));
  SettleProgress where = settle_progress_of(read);
  EXPECT_EQ(where.steps, stop_after);
  Settled out{settle_packing(*nscd, scene, progress, nullptr, &where), {}};
  EXPECT_TRUE(where.finished);
  out.state = nscd->save_state();
  return out;
}

bool same_bits(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

void expect_same_settle(const Settled& whole, const Settled& resumed) {
  EXPECT_EQ(resumed.summary.at_rest, whole.summary.at_rest);
  EXPECT_EQ(resumed.summary.ended_by, whole.summary.ended_by);
  EXPECT_EQ(resumed.summary.steps, whole.summary.steps);
  EXPECT_EQ(resumed.summary.time_s, whole.summary.time_s);
  EXPECT_EQ(resumed.summary.max_speed_m_s, whole.summary.max_speed_m_s);
  EXPECT_EQ(resumed.summary.rattlers, whole.summary.rattlers);
  EXPECT_TRUE(same_bits(resumed.state.position_m, whole.state.position_m));
  EXPECT_TRUE(same_bits(resumed.state.velocity_m_per_s, whole.state.velocity_m_per_s));
  EXPECT_TRUE(same_bits(resumed.state.candidate_force_N, whole.state.candidate_force_N));
  EXPECT_EQ(resumed.state.stats.steps, whole.state.stats.steps);
  EXPECT_EQ(resumed.state.stats.unconverged_steps, whole.state.stats.unconverged_steps);
}

// The scene settled whole under `rest_test`, then stopped after each of stops(n) steps (n: the
// whole settle's) and resumed: each ends as the whole settle.
void expect_resumes_as_whole(const std::string& rest_test, const std::function<std::vector<int>(int)>& stops) {
  const auto dir = fs::temp_directory_path() / ("tmdem_settle_resume_" + rest_test);
  fs::create_directories(dir);
  const Scene scene = dropped_spheres(rest_test);
  const Settled whole = settle_whole(scene);
  ASSERT_TRUE(whole.summary.at_rest);
  ASSERT_EQ(whole.summary.ended_by, rest_test);
  const int n = int(whole.summary.steps);
  ASSERT_GT(n, 20);  // a fall and a window to fill: the stops are all inside the settle
  for (const int stop_after : stops(n)) {
    SCOPED_TRACE("stopped after " + std::to_string(stop_after) + " of " + std::to_string(n) + " steps");
    const Settled resumed = settle_in_two(scene, stop_after, (dir / "settle.checkpoint.h5").string());
    expect_same_settle(whole, resumed);
  }
  fs::remove_all(dir);
}

TEST(SettleResume, StoppedAnywhereAndResumedFromItsCheckpointEndsAsTheWholeSettle) {
  // Early (the fall), midway, and within the rest test's last window (5 steps): a resume that
  // forgot the window would come to rest later.
  expect_resumes_as_whole("network", [](int n) { return std::vector<int>{1, n / 2, n - 3, n - 1}; });
}

TEST(SettleResume, VelocityRestTestResumesToTheSameStep) {
  expect_resumes_as_whole("velocity", [](int n) { return std::vector<int>{n - 2}; });
}

// The window comes back as it was written, and a window longer than the test's is refused.
TEST(SettleResume, RestWindowRoundTripsAndAnOverlongOneIsRefused) {
  SettleProgress p;
  p.time_s = 0.123;
  p.steps = 123;
  p.unconverged_steps = 4;
  p.max_penetration_m = 1.5e-7;
  p.rest_window.push_back({{{0, 1}, {0, 2}}, {1.0, 2.0}});
  p.rest_window.push_back({{}, {}});
  p.rest_window.push_back({{{3, -1}}, {0.25}});
  CheckpointState cs;
  store_settle_progress(p, cs);
  const SettleProgress back = settle_progress_of(cs);
  EXPECT_EQ(back.time_s, p.time_s);
  EXPECT_EQ(back.steps, p.steps);
  EXPECT_EQ(back.unconverged_steps, p.unconverged_steps);
  EXPECT_EQ(back.max_penetration_m, p.max_penetration_m);
  ASSERT_EQ(back.rest_window.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(back.rest_window[s].pair, p.rest_window[s].pair);
    EXPECT_EQ(back.rest_window[s].normal_force_N, p.rest_window[s].normal_force_N);
  }
  SettleRestTest test({.window_steps = 1});
  EXPECT_THROW(test.restore_history(back.rest_window), std::invalid_argument);
  std::deque<SettleRestTest::Snapshot> uneven{{{{0, 1}}, {}}};
  EXPECT_THROW(SettleRestTest({.window_steps = 5}).restore_history(uneven), std::invalid_argument);
}

}  // namespace
}  // namespace tmdem::coupling
