// End to end: every heat-transfer mode of the contract from a scene file, with an exact energy
// balance, cvode and ida agreeing on held temperatures, and switched-off sections ignored.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

std::string scene(const std::string& effects, const std::string& extra) {
  return R"(format = "tmdem-scene-1"
[simulation]
duration = 200.0
[effects]
mechanics = "off"
)" + effects + R"(
[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
conductivity = 50.0
heat_capacity = 460.0
emissivity = 0.8
[[generate]]
kind = "column"
count = 6
radius = 0.001
origin = [0.0, 0.001, 0.0]
material = "steel"
temperature = 293.15
[[assign]]
ids = [5]
heat_source = 0.01
[[assign]]
ids = [2]
temperature = 350.0
fixed_temperature = true
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "steel"
temperature = 400.0
[thermal]
conductance = "constant"
constant_conductance = 1.0e-3
relative_tolerance = 1.0e-10
absolute_tolerance = 1.0e-10
[output]
file = "out.h5"
interval = 20.0
)" + extra;
}

nlohmann::json summary_of(const std::string& dir) {
  return read_summary(dir + "/s.json");
}

std::vector<double> final_temperatures(const std::string& dir) {
  H5::H5File f(dir + "/out.h5", H5F_ACC_RDONLY);
  const auto T = read_doubles(f, "/frames/temperature");
  return {T.end() - 6, T.end()};
}

}  // namespace

TEST(EndToEndModes, EveryModeRunsWithExactEnergyBalanceAndHeldTemperature) {
  const std::string effects = "convection = true\nradiation = true\n";
  const std::string sections = R"([convection]
coefficient = 50.0
fluid_temperature = 300.0
[radiation]
ambient_temperature = 280.0
)";
  std::vector<double> T_cvode;
  for (const std::string integrator : {"cvode", "ida"}) {
    const auto dir = scratch_dir("modes_" + integrator);
    write_file(dir + "/s.toml", scene(effects, sections));
    const auto r = run_tmdem("run s.toml --quiet --summary s.json --set thermal.integrator=" + integrator, dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto s = summary_of(dir);
    EXPECT_LT(s["energy"]["balance_error_rel"].get<double>(), 1e-8) << integrator;
    EXPECT_GT(std::abs(s["energy"]["boundary_heat_J"].get<double>()), 1e-3);
    const auto T = final_temperatures(dir);
    EXPECT_EQ(T[2], 350.0) << "held particle moved with " << integrator;
    for (double x : T) {
      EXPECT_GT(x, 280.0);
      EXPECT_LT(x, 1000.0);
    }
    if (T_cvode.empty()) {
      T_cvode = T;
    } else {
      for (int i = 0; i < 6; ++i) EXPECT_NEAR(T[i], T_cvode[i], 1e-6) << "cvode and ida disagree";
    }
  }
}

TEST(EndToEndModes, SectionsOfSwitchedOffModesChangeNothing) {
  const std::string sections = R"([convection]
coefficient = 5000.0
fluid_temperature = 1000.0
[radiation]
ambient_temperature = 2000.0
)";
  const auto plain = scratch_dir("modes_plain");
  const auto with = scratch_dir("modes_with");
  write_file(plain + "/s.toml", scene("", ""));
  write_file(with + "/s.toml", scene("convection = false\nradiation = false\n", sections));
  ASSERT_EQ(run_tmdem("run s.toml --quiet --summary s.json", plain).exit_code, 0);
  const auto r = run_tmdem("run s.toml --summary s.json", with);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("convection"), std::string::npos) << "a switched-off mode was built: " << r.output;
  EXPECT_EQ(r.output.find("radiation"), std::string::npos) << r.output;
  EXPECT_EQ(final_temperatures(plain), final_temperatures(with));
}
