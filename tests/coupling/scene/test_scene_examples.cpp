// Defaults, TOML syntax errors, files, the examples and the built-in default scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "coupling/scene/DefaultScene.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(TMDEM_SOURCE_DIR) / "examples";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SceneDefaults, MinimalScene) {
  const Scene scene = load_scene_text(R"(format = "tmdem-scene-1"
[simulation]
duration = 100
[[material]]
name = "m"
density = 1000.0
young_modulus = 1e9
poisson_ratio = 0.25
conductivity = 1.0
heat_capacity = 1000.0
[[particle]]
position = [0.0, 0.0, 0.0]
radius = 0.01
material = "m"
)",
                                      "min.toml");
  EXPECT_EQ(scene.duration_s, 100.0);
  EXPECT_EQ(scene.dimension, 3);
  EXPECT_EQ(scene.gravity_m_per_s2, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_EQ(scene.seed, 1u);
  EXPECT_EQ(scene.effects.mechanics, MechanicsMode::Settle);
  EXPECT_TRUE(scene.effects.on("conduction"));
  EXPECT_FALSE(scene.effects.on("convection"));
  EXPECT_FALSE(scene.effects.on("radiation"));
  EXPECT_EQ(scene.materials[0].friction, 0.3);
  EXPECT_EQ(scene.materials[0].emissivity, 0.0);
  const Particle& p = scene.particles[0];
  EXPECT_EQ(p.temperature_K, 293.15);
  EXPECT_FALSE(p.fixed_temperature);
  EXPECT_EQ(p.heat_source_W, 0.0);
  EXPECT_FALSE(p.fixed);
  EXPECT_EQ(p.material, 0);
  EXPECT_EQ(scene.heat_modes.find("convection", "coefficient").value(), 10.0);
  EXPECT_EQ(scene.heat_modes.find("convection", "fluid_temperature").value(), 293.15);
  EXPECT_EQ(scene.heat_modes.find("radiation", "ambient_temperature").value(), 293.15);
  EXPECT_EQ(scene.mechanics.time_step_s, 1e-3);
  EXPECT_EQ(scene.mechanics.theta, 0.5);
  EXPECT_EQ(scene.mechanics.tolerance, 1e-5);
  EXPECT_EQ(scene.mechanics.fall_tolerance, 1e-4);
  EXPECT_EQ(scene.mechanics.fall_speed_m_per_s, 0.0);  // automatic
  EXPECT_EQ(scene.mechanics.max_iterations, 10000);
  EXPECT_EQ(scene.mechanics.settle_time_s, 5.0);
  EXPECT_EQ(scene.mechanics.settle_velocity_m_per_s, 1e-4);
  EXPECT_EQ(scene.thermal.integrator, "cvode");
  EXPECT_FALSE(scene.thermal.linear_solver.has_value());  // "auto": resolved per run, klu here
  EXPECT_EQ(scene.thermal.relative_tolerance, 1e-6);
  EXPECT_EQ(scene.thermal.absolute_tolerance_K, 1e-6);
  EXPECT_EQ(scene.thermal.explicit_step_s, 0.0);
  EXPECT_EQ(scene.thermal.conductance, thermal::ConductanceLawKind::Hertz);
  EXPECT_EQ(scene.thermal.constant_conductance_W_per_K, 1e-4);
  EXPECT_EQ(scene.output.file, "result.h5");
  EXPECT_EQ(scene.output.interval_s, 0.1);
  EXPECT_TRUE(scene.output.contacts);
  EXPECT_EQ(scene.output.checkpoint_interval_s, 0.0);
  EXPECT_TRUE(scene.walls.empty());
  EXPECT_EQ(scene.source, "min.toml");
  EXPECT_FALSE(scene.resolved_toml.empty());
}

TEST(SceneSyntax, ErrorNamesFileLineAndColumn) {
  const std::string message =
      scene_error("format = \"tmdem-scene-1\"\n[simulation]\nduration = = 3\n");
  EXPECT_NE(message.find("test.toml:3:12: TOML syntax error"), std::string::npos) << message;
  EXPECT_NE(message.find("TOML syntax error"), std::string::npos) << message;
  const std::string column = scene_error("format = \"tmdem-scene-1\"\nx = [1, 2\n");
  EXPECT_NE(column.find("test.toml:"), std::string::npos) << column;
}

TEST(SceneSyntax, ErrorLineAndColumnExact) {
  // toml++ reports the unterminated string where it meets the end of line 2.
  const std::string message = scene_error("a = 1\nb = \"oops\nc = 2\n");
  EXPECT_NE(message.find("test.toml:2:10: TOML syntax error"), std::string::npos) << message;
  const std::string twice = scene_error("[simulation]\nduration = 1\n[simulation]\n");
  EXPECT_NE(twice.find("test.toml:3:1: TOML syntax error"), std::string::npos) << twice;
}

TEST(SceneFiles, MissingFileNamed) {
  try {
    load_scene_file("/nonexistent/dir/bed.toml");
    FAIL() << "no SceneError";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/dir/bed.toml"), std::string::npos)
        << error.what();
  }
}

TEST(SceneFiles, LocationsUseTheFilePath) {
  const auto path = std::filesystem::temp_directory_path() / "tmdem_test_scene_location.toml";
  {
    std::ofstream out(path);
    out << kBaseScene << "\n[thermal]\nintegrator = \"rk4\"\n";
  }
  try {
    load_scene_file(path.string());
    FAIL() << "no SceneError";
  } catch (const SceneError& error) {
    const auto lines = std::count(kBaseScene.begin(), kBaseScene.end(), '\n');
    const std::string expected = path.string() + ":" + std::to_string(lines + 3) +
                                 ":14: thermal.integrator: must be one of";
    EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
  }
  std::filesystem::remove(path);
}

TEST(SceneExamples, AllLoad) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".toml") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    try {
      const Scene scene = load_scene_file(entry.path().string());
      EXPECT_FALSE(scene.particles.empty());
      EXPECT_EQ(scene.source, entry.path().string());
    } catch (const SceneError& error) {
      ADD_FAILURE() << error.what();
    }
  }
  EXPECT_GE(count, 3);
}

TEST(SceneExamples, ResolvedTomlIsReadableAndReadsBack) {
  for (const char* name : {"paper_bed.toml", "paper_triangle.toml", "lattice_constant.toml"}) {
    SCOPED_TRACE(name);
    const Scene scene = load_scene_file((kExamples / name).string());
    const toml::table original = toml::parse_file((kExamples / name).string());
    const toml::table resolved = toml::parse(scene.resolved_toml);
    EXPECT_EQ(original, resolved) << scene.resolved_toml;
  }
  const Scene bed = load_default_scene();
  EXPECT_NE(bed.resolved_toml.find("gravity = [0.0, -9.81, 0.0]"), std::string::npos)
      << bed.resolved_toml;
  EXPECT_NE(bed.resolved_toml.find("tolerance = 1e-06"), std::string::npos) << bed.resolved_toml;
  EXPECT_NE(bed.resolved_toml.find("box = { max = [0.029, 0.045, 0.0], min = [0.001, 0.001, 0.0] }"),
            std::string::npos)
      << bed.resolved_toml;
}

TEST(SceneExamples, PaperTriangle) {
  const Scene scene = load_scene_file((kExamples / "paper_triangle.toml").string());
  ASSERT_EQ(scene.particles.size(), 14u);
  EXPECT_EQ(scene.dimension, 2);
  EXPECT_EQ(scene.effects.mechanics, MechanicsMode::Settle);
  EXPECT_EQ(scene.thermal.conductance, thermal::ConductanceLawKind::Hertz);
  EXPECT_EQ(scene.particles[0].temperature_K, 373.15);
  for (std::size_t i = 1; i < 14; ++i) EXPECT_EQ(scene.particles[i].temperature_K, 293.15);
  EXPECT_EQ(scene.walls.size(), 3u);
}

TEST(SceneExamples, LatticeConstant) {
  const Scene scene = load_scene_file((kExamples / "lattice_constant.toml").string());
  ASSERT_EQ(scene.particles.size(), 64u);
  EXPECT_EQ(scene.effects.mechanics, MechanicsMode::Off);
  EXPECT_EQ(scene.thermal.conductance, thermal::ConductanceLawKind::Constant);
  EXPECT_EQ(scene.thermal.integrator, "cvode");
  EXPECT_EQ(scene.duration_s, 50.0);
  EXPECT_EQ(scene.particles[0].temperature_K, 373.15);
  for (std::size_t i = 1; i < 64; ++i) EXPECT_EQ(scene.particles[i].temperature_K, 293.15);
}

TEST(SceneExamples, DefaultSceneIsPaperBed) {
  EXPECT_EQ(std::string(default_scene_toml()), read_text(kExamples / "paper_bed.toml"));
}

TEST(SceneExamples, DefaultSceneLoads) {
  const Scene scene = load_default_scene();
  EXPECT_EQ(scene.source, "<default scene>");
  ASSERT_EQ(scene.particles.size(), 256u);
  EXPECT_EQ(scene.dimension, 2);
  EXPECT_EQ(scene.output.file, "tmdem-default.h5");
  int heated = 0;
  for (const auto& p : scene.particles) {
    EXPECT_GE(p.radius_m, 0.0005);
    EXPECT_LE(p.radius_m, 0.001);
    if (p.temperature_K == 373.15) ++heated;
  }
  EXPECT_EQ(heated, 3);
}

}  // namespace
}  // namespace tmdem::coupling::test
