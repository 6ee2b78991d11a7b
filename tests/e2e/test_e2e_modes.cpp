// End to end: every heat-transfer mode of the contract from a scene file, with an exact energy
// balance, cvode and ida agreeing on held temperatures, and switched-off sections ignored.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>
#include <sstream>
#include <tuple>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// Six steel spheres on a 400 K floor: a heat source on top, one held particle in the middle.
SceneBuilder scene() {
  return thermal_scene()
      .set("simulation.duration", 200.0)
      .set("material[0].emissivity", 0.8)
      .add("generate", column(6))
      .add("assign", assign_ids({5}, {{"heat_source", 0.01}}))
      .add("assign", assign_ids({2}, {{"temperature", 350.0}, {"fixed_temperature", true}}))
      .add("wall", floor_wall({{"temperature", 400.0}}))
      .set(tolerances(1.0e-10))
      .set(output("out.h5", 20.0));
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
  const TomlKeys effects = {{"effects.convection", true}, {"effects.radiation", true}};
  const TomlKeys sections = {{"convection.coefficient", 50.0},
                             {"convection.fluid_temperature", 300.0},
                             {"radiation.ambient_temperature", 280.0}};
  std::vector<double> T_cvode;
  for (const std::string integrator : {"cvode", "ida"}) {
    const auto dir = scratch_dir("modes_" + integrator);
    write_file(dir + "/s.toml", scene().set(effects).set(sections));
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
  const TomlKeys sections = {{"convection.coefficient", 5000.0},
                             {"convection.fluid_temperature", 1000.0},
                             {"radiation.ambient_temperature", 2000.0}};
  const auto plain = scratch_dir("modes_plain");
  const auto with = scratch_dir("modes_with");
  write_file(plain + "/s.toml", scene());
  write_file(with + "/s.toml",
             scene().set({{"effects.convection", false}, {"effects.radiation", false}}).set(sections));
  ASSERT_EQ(run_tmdem("run s.toml --quiet --summary s.json", plain).exit_code, 0);
  const auto r = run_tmdem("run s.toml --summary s.json", with);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("convection"), std::string::npos) << "a switched-off mode was built: " << r.output;
  EXPECT_EQ(r.output.find("radiation"), std::string::npos) << r.output;
  EXPECT_EQ(final_temperatures(plain), final_temperatures(with));
}

TEST(EndToEndModes, ProductionBinaryNeitherContainsNorHonoursTheTestOnlyFaultMode) {
  // The fault_injection mode is registered only by tmdem_testing.
  std::ifstream binary(TMDEM_BINARY, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(binary)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100000u);
  EXPECT_EQ(bytes.find("after_rhs_evaluations"), std::string::npos);
  EXPECT_EQ(bytes.find("TMDEM_FAULT_AFTER_RHS_EVALS"), std::string::npos);

  const auto dir = scratch_dir("modes_fault_refused");
  write_file(dir + "/s.toml", scene().set("effects.fault_injection", true));
  const auto r = run_tmdem("check s.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("effects.fault_injection: unknown key"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("valid keys here: mechanics, conduction, convection, radiation"),
            std::string::npos)
      << r.output;
}

TEST(EndToEndModes, ARegisteredModeValidatesItsOwnKeysWithExitTwo) {
  // tmdem_testing registers fault_injection: its section is read and checked by its own
  // declaration (range >= 0, and its own check: a whole number).
  const auto dir = scratch_dir("modes_fault_keys");
  const std::string testing = std::string("'") + TMDEM_TESTING_BINARY + "' ";
  auto run_testing = [&](const std::string& args) {
    const std::string cmd = "cd '" + dir + "' && " + testing + args + " > log.txt 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(dir + "/log.txt");
    std::stringstream text;
    text << in.rdbuf();
    return std::pair{WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
  };
  write_file(dir + "/s.toml", scene()
                                  .set("effects.fault_injection", true)
                                  .set("fault_injection.after_rhs_evaluations", -3));
  auto [code, log] = run_testing("check s.toml");
  EXPECT_EQ(code, 2) << log;
  EXPECT_NE(log.find("fault_injection.after_rhs_evaluations: must be >= 0 (got -3)"),
            std::string::npos) << log;
  write_file(dir + "/s.toml", scene()
                                  .set("effects.fault_injection", true)
                                  .set("fault_injection.after_rhs_evaluations", 2.5));
  std::tie(code, log) = run_testing("check s.toml");
  EXPECT_EQ(code, 2) << log;
  EXPECT_NE(log.find("fault_injection.after_rhs_evaluations: must be a whole number (got 2.5)"),
            std::string::npos) << log;
  std::tie(code, log) = run_testing("check s.toml --set fault_injection.after_rhs_evaluations=7");
  EXPECT_EQ(code, 0) << log;
  EXPECT_NE(log.find("effects: mechanics off, conduction on, convection off, radiation off, "
                     "gas_conduction off, friction_heat off, fault_injection on"),
            std::string::npos) << log;
  EXPECT_NE(log.find("modes: contact_conduction wall_conduction heat_source fault_injection"),
            std::string::npos) << log;
}

TEST(EndToEndModes, DocsSceneCommandPrintsTheCommittedReference) {
  const auto dir = scratch_dir("docs_scene");
  const auto r = run_tmdem("docs scene", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/docs/scene.md");
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_TRUE(r.output == committed.str())
      << "docs/scene.md differs from `tmdem docs scene`; regenerate it with:\n"
         "  build/tmdem docs scene > docs/scene.md";
}
