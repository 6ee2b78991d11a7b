// `tmdem contact-problem` writes the run's own steps: it settles with steps of exactly
// mechanics.time_step, as `tmdem run` does. It had stepped by (k + 1) h - k h, which is not h to
// the bit (0.078 - 0.077 = 0.001 + 9e-19), so its trajectory drifted from the run's:
// piston_cylinder's step 78 was still solved at the fall's tolerance there, where the run had
// tightened to 1e-5 and stalled.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "e2e/E2eSupport.h"

namespace tmdem::e2e {
namespace {

// 60 glass spheres poured from up to 5 cm into a 12 mm box: well over 78 steps of 1 ms to rest.
const char* kSettlingPour = R"(format = "tmdem-scene-1"
[simulation]
duration = 1e-3
gravity = [0.0, -9.81, 0.0]
seed = 3
[effects]
mechanics = "settle"
[[material]]
name = "glass"
density = 2500.0
young_modulus = 6.3e10
poisson_ratio = 0.22
friction = 0.4
conductivity = 1.0
heat_capacity = 800.0
[[generate]]
kind = "random"
count = 60
box = { min = [0.001, 0.01, 0.001], max = [0.011, 0.05, 0.011] }
radii = [0.0008, 0.001]
fractions = [0.5, 0.5]
material = "glass"
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "glass"
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
material = "glass"
[[wall]]
point = [0.012, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
material = "glass"
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "glass"
[[wall]]
point = [0.0, 0.0, 0.012]
normal = [0.0, 0.0, -1.0]
material = "glass"
)";

template <class T>
T read_scalar(const std::string& path, const std::string& name, const H5::PredType& type) {
  H5::H5File file(path, H5F_ACC_RDONLY);
  T value{};
  file.openDataSet(name).read(&value, type);
  return value;
}

}  // namespace

TEST(E2eContactProblem, SettleStepsAreTheRunsOwn) {
  const auto dir = scratch_dir("contact_problem_steps");
  write_file(dir + "/pour.toml", kSettlingPour);
  const auto run = run_tmdem("run pour.toml -o r.h5 --summary s.json --quiet", dir);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = nlohmann::json::parse(text_of(dir + "/s.json"));
  const auto steps = summary["mechanics"]["steps"].get<std::int64_t>();
  ASSERT_GT(steps, 78) << "the pour must still be settling at step 78";

  // Step 78 (t = 0.078 s): taken with h itself.
  const auto at78 = run_tmdem("contact-problem pour.toml --step 78 -o p78.hdf5", dir);
  ASSERT_EQ(at78.exit_code, 0) << at78.output;
  EXPECT_EQ(read_scalar<double>(dir + "/p78.hdf5", "/tmdem/time_step", H5::PredType::NATIVE_DOUBLE), 1e-3);
  EXPECT_EQ(read_scalar<std::int64_t>(dir + "/p78.hdf5", "/tmdem/step", H5::PredType::NATIVE_INT64), 78);

  // The settle's last step: the step the run came to rest at, with the run's Siconos residual
  // for it among the run's (the same trajectory to the bit ends at the same step).
  const auto last = run_tmdem("contact-problem pour.toml --step last -o last.hdf5", dir);
  ASSERT_EQ(last.exit_code, 0) << last.output;
  EXPECT_EQ(read_scalar<std::int64_t>(dir + "/last.hdf5", "/tmdem/step", H5::PredType::NATIVE_INT64), steps);
  EXPECT_LE(read_scalar<double>(dir + "/last.hdf5", "/tmdem/siconos_residual", H5::PredType::NATIVE_DOUBLE),
            summary["mechanics"]["max_siconos_residual"].get<double>());
}

}  // namespace tmdem::e2e
