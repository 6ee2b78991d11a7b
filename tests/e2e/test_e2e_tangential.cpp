// End to end: /contacts/tangential_force [C,3] holds the tangential part of the reaction the
// mechanics computed. A sphere on an incline steeper than its rolling limit (tan(theta) > 7/2 mu
// for a solid sphere) slides: Coulomb's law gives |f_t| = mu f_n exactly, f_t up the slope and
// orthogonal to the wall normal, and f_n = m g cos(theta). Without mechanics it is 0.
#include <gtest/gtest.h>

#include <cmath>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

TEST(EndToEndTangential, SlidingSphereOnInclineCarriesMuTimesNormalForce) {
  const double theta = M_PI / 6.0, mu = 0.1, r = 0.001, rho = 7800.0, g = 9.81;
  const double n[3] = {-std::sin(theta), std::cos(theta), 0.0};  // wall normal, into the domain
  const double up[3] = {std::cos(theta), std::sin(theta), 0.0};  // up the slope
  using namespace tmdem::test;
  const std::string scene =
      SceneBuilder()
          .set({{"simulation.duration", 0.02},
                {"simulation.gravity", {0.0, -g, 0.0}},
                {"effects.mechanics", "dynamic"},
                {"mechanics.time_step", 1.0e-4},
                {"mechanics.tolerance", 1.0e-10},
                {"output.file", "out.h5"},
                {"output.interval", 0.005}})
          .add("material", steel({{"friction", mu}}))
          .add("particle", particle({n[0] * r * (1 + 1e-12), n[1] * r * (1 + 1e-12), 0.0}))
          .add("wall", plane_wall({0.0, 0.0, 0.0}, {n[0], n[1], 0.0}))
          .str();
  const auto dir = scratch_dir("tangential");
  write_file(dir + "/s.toml", scene);
  const auto run = run_tmdem("run s.toml --quiet", dir);
  ASSERT_EQ(run.exit_code, 0) << run.output;

  H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto ft = read_doubles(file, "/contacts/tangential_force", &dims);
  const auto fn = read_doubles(file, "/contacts/normal_force");
  const auto pair = read_ints(file, "/contacts/pair");
  ASSERT_EQ(dims.size(), 2u);
  EXPECT_EQ(dims[1], 3u);
  ASSERT_EQ(dims[0], fn.size());
  ASSERT_GE(fn.size(), 3u);  // frames after t = 0 each hold the sphere-wall contact
  EXPECT_EQ(read_string_attribute(file.openDataSet("/contacts/tangential_force"), "units"), "N");
  const double m = rho * 4.0 / 3.0 * M_PI * r * r * r;
  for (std::size_t c = 0; c < fn.size(); ++c) {
    SCOPED_TRACE(c);
    EXPECT_EQ(pair[2 * c], 0);
    EXPECT_EQ(pair[2 * c + 1], -1);
    const double t[3] = {ft[3 * c], ft[3 * c + 1], ft[3 * c + 2]};
    const double magnitude = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    EXPECT_NEAR(magnitude, mu * fn[c], 1e-9 * fn[c]);
    EXPECT_NEAR(fn[c], m * g * std::cos(theta), 1e-6 * m * g);
    EXPECT_NEAR(t[0] * n[0] + t[1] * n[1] + t[2] * n[2], 0.0, 1e-12 * fn[c]);
    EXPECT_GT(t[0] * up[0] + t[1] * up[1] + t[2] * up[2], 0.99 * magnitude);
  }
}

TEST(EndToEndTangential, WithoutMechanicsTangentialForceIsZero) {
  const auto dir = scratch_dir("tangential_off");
  using namespace tmdem::test;
  write_file(dir + "/s.toml", thermal_scene()
                                  .set(output("out.h5", 0.5))
                                  .add("generate", column(3))
                                  .str());
  ASSERT_EQ(run_tmdem("run s.toml --quiet", dir).exit_code, 0);
  H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto ft = read_doubles(file, "/contacts/tangential_force", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{6, 3}));  // 2 contacts in each of 3 frames
  for (double v : ft) EXPECT_EQ(v, 0.0);
}

}  // namespace
