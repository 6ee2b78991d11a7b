// settle_packing (ThermalProblem.h) reports each settle's own unconverged steps: a conductivity
// study settles the same integrator once per load, and the second load's line and warnings
// must not carry the first load's steps (its line once printed the integrator's running total).
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>

#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;

// 30 steel spheres (1 mm) dropped onto a floor, one sweep per step: the impacts leave steps
// unconverged (not retaken in parts: one step, one count). Settled for 20 steps, too short to
// come to rest.
Scene dropped_spheres() {
  const auto text = steel_scene()
                        .set({{"effects.mechanics", "settle"},
                              {"simulation.gravity", {0.0, -9.81, 0.0}},
                              {"mechanics.max_iterations", 1},
                              {"mechanics.retry_parts", 1},
                              {"mechanics.settle_time", 0.02},
                              {"thermal.conductance", "constant"},
                              {"thermal.constant_conductance", 1.0e-3}})
                        .add("generate", random_fill(30, "{ min = [0.0, 0.0, 0.0], max = [0.012, 0.008, 0.012] }",
                                                     {{"radius", 0.001}}))
                        .add("wall", floor_wall())
                        .str();
  return load_scene_text(text, "scene.toml");
}

// "(N steps, M unconverged)" of the not-at-rest line: {N, M}.
std::pair<long, long> counts_of(const std::string& printed) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(printed, m, std::regex(R"(\((\d+) steps, (\d+) unconverged\))"))) << printed;
  return m.size() == 3 ? std::pair{std::stol(m[1]), std::stol(m[2])} : std::pair{-1L, -1L};
}

TEST(SettleCounts, EachSettleCountsItsOwnUnconvergedSteps) {
  const Scene scene = dropped_spheres();
  auto nscd = make_nscd_integrator(scene, make_particle_set(scene));
  std::int64_t before = 0;
  for (int load = 0; load < 2; ++load) {
    SCOPED_TRACE(load);
    std::ostringstream sink;
    ProgressReporter progress(sink, false, false);
    const SettleSummary settled = settle_packing(*nscd, scene, progress);
    ASSERT_FALSE(settled.at_rest);
    const std::string printed = sink.str();
    const auto [steps, unconverged] = counts_of(printed);
    EXPECT_EQ(steps, settled.steps);
    EXPECT_EQ(unconverged, nscd->stats().unconverged_steps - before);
    EXPECT_GE(unconverged, 1);  // the test means something only with unconverged steps
    EXPECT_LE(unconverged, steps);
    // Up to 10 warnings for each settle, the second's as the first's.
    const std::regex warning("settle step at");
    const auto warnings = std::distance(std::sregex_iterator(printed.begin(), printed.end(), warning),
                                        std::sregex_iterator());
    EXPECT_EQ(warnings, std::min<long>(unconverged, 10));
    before = nscd->stats().unconverged_steps;
  }
}

}  // namespace
}  // namespace tmdem::coupling
