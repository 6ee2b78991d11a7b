// A packing settled by tmdem goes out and comes back: `tmdem export` writes the last frame as
// CSV, [[import]] reads it (and the result file directly) into another scene, bit for bit, and
// that scene runs. The settled bed overlaps beyond the default 1e-9 of the radius, so the
// import needs (and reports) its overlap_tolerance.
#include <gtest/gtest.h>

#include "E2eSupport.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"

namespace tmdem::e2e {
namespace {

// examples/poured_bed.toml with [[generate]] replaced by an [[import]] of `keys`.
std::string imported_bed(const std::string& import_keys) {
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/examples/poured_bed.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto a = s.find("[[generate]]"), b = s.find("[[wall]]");
  return s.substr(0, a) + "[[import]]\n" + import_keys + "\n\n" + s.substr(b);
}

// examples/poured_bed.toml settled into bed.h5 until every particle is still (rest_test
// "velocity": the network test may freeze a bed while a rattler still creeps).
const std::string kSettleBed =
    "run " + std::string(TMDEM_SOURCE_DIR) +
    "/examples/poured_bed.toml -o bed.h5 --quiet --set effects.mechanics=\"settle\" "
    "--set simulation.duration=0.1 --set mechanics.rest_test=\"velocity\"";

TEST(E2eImport, SettledBedExportedAndImportedBackRuns) {
  const std::string dir = scratch_dir("import");
  ASSERT_EQ(run_tmdem(kSettleBed, dir).exit_code, 0);
  const auto exported = run_tmdem("export bed.h5 -o bed.csv", dir);
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_NE(exported.output.find("exported 80 particles, frame 2 of 3 (t = 0.1 s)"),
            std::string::npos) << exported.output;
  // Refusals: an existing CSV, a frame the file does not hold.
  EXPECT_EQ(run_tmdem("export bed.h5 -o bed.csv", dir).exit_code, 2);
  const auto frame = run_tmdem("export bed.h5 --frame 3 -o f.csv", dir);
  EXPECT_EQ(frame.exit_code, 2);
  EXPECT_NE(frame.output.find("has frames 0 to 2"), std::string::npos) << frame.output;

  // The CSV and the result file give the same particles, bit for bit, equal to the last frame.
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const auto from_csv = coupling::load_scene_text(
      imported_bed("file = \"bed.csv\"\noverlap_tolerance = 0.01"), "csv.toml");
  const auto from_h5 = coupling::load_scene_text(
      imported_bed("file = \"bed.h5\"\noverlap_tolerance = 0.01"), "h5.toml");
  const H5::H5File result(dir + "/bed.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto position = read_doubles(result, "/frames/position", &dims);
  const auto temperature = read_doubles(result, "/frames/temperature");
  const auto radius = read_doubles(result, "/particles/radius");
  ASSERT_EQ(from_csv.particles.size(), 80u);
  ASSERT_EQ(from_h5.particles.size(), 80u);
  const std::size_t last = (dims[0] - 1) * 80;
  for (std::size_t i = 0; i < 80; ++i) {
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(from_csv.particles[i].position_m[d], position[3 * (last + i) + d]);
      EXPECT_EQ(from_h5.particles[i].position_m[d], position[3 * (last + i) + d]);
    }
    EXPECT_EQ(from_csv.particles[i].radius_m, radius[i]);
    EXPECT_EQ(from_h5.particles[i].radius_m, radius[i]);
    EXPECT_EQ(from_csv.particles[i].temperature_K, temperature[last + i]);
    EXPECT_EQ(from_h5.particles[i].temperature_K, temperature[last + i]);
  }
  EXPECT_EQ(from_csv.imports[0].largest_overlap, from_h5.imports[0].largest_overlap);
  EXPECT_GT(from_csv.imports[0].largest_overlap, 1e-9);  // why the tolerance is needed
  EXPECT_LT(from_csv.imports[0].largest_overlap, 0.01);
  // Without the tolerance the settled bed is refused, naming the key to raise.
  try {
    coupling::load_scene_text(imported_bed("file = \"bed.csv\""), "strict.toml");
    ADD_FAILURE() << "the settled bed loaded with the default tolerance";
  } catch (const coupling::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("import[0].overlap_tolerance = 1e-09"), std::string::npos)
        << e.what();
  }

  std::filesystem::current_path(previous);

  // The imported bed runs (it is already at rest) and reports its largest overlap.
  write_file(dir + "/again.toml", imported_bed("file = \"bed.csv\"\noverlap_tolerance = 0.01"));
  const auto again = run_tmdem("run again.toml -o again.h5 --summary again.json", dir);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("import[0]: 80 particles (ids 0-79) from bed.csv (csv); largest "
                              "overlap"), std::string::npos) << again.output;
  const auto summary = read_summary(dir + "/again.json");
  EXPECT_EQ(summary["status"].get<std::string>(), "ok");
  EXPECT_LT(summary["energy"]["balance_error_rel"].get<double>(), 1e-9);
  ASSERT_EQ(summary["imports"].size(), 1u);
  EXPECT_EQ(summary["imports"][0]["file"].get<std::string>(), "bed.csv");
  EXPECT_EQ(summary["imports"][0]["particles"].get<int>(), 80);
  EXPECT_EQ(summary["imports"][0]["largest_overlap_rel"].get<double>(),
            from_csv.imports[0].largest_overlap);
  EXPECT_EQ(summary["imports"][0]["overlap_tolerance"].get<double>(), 0.01);
  // poured_bed is dynamic: the imported bed starts exactly where the export left it and stays
  // at rest for its 1 s (measured: 1.5e-7 m at most, 3e-4 of the smallest radius; settled
  // until every particle was still, rest_test "velocity": with "network" a particle may still
  // creep when frozen, and the bed moved 6.4e-7 m).
  const H5::H5File run(dir + "/again.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> run_dims;
  const auto moved = read_doubles(run, "/frames/position", &run_dims);
  const std::size_t end = (run_dims[0] - 1) * 80 * 3;
  double largest = 0.0;
  for (std::size_t k = 0; k < 80 * 3; ++k) {
    EXPECT_EQ(moved[k], position[3 * last + k]);
    largest = std::max(largest, std::abs(moved[end + k] - moved[k]));
  }
  EXPECT_LT(largest, 1e-3 * 5e-4);
}

// A bed settled by tmdem until every particle was still, exported and imported into a settle
// run at the defaults: the contact network's forces are found again at once, so the network
// rest test ends the settling within a few windows (at most 10 steps), every step converged.
TEST(E2eImport, SettledBedImportedIntoASettleRunReSettlesWithinTenSteps) {
  const std::string dir = scratch_dir("import_resettle");
  ASSERT_EQ(run_tmdem(kSettleBed, dir).exit_code, 0);
  ASSERT_EQ(run_tmdem("export bed.h5 -o bed.csv", dir).exit_code, 0);
  write_file(dir + "/again.toml", imported_bed("file = \"bed.csv\"\noverlap_tolerance = 0.01"));
  const auto again = run_tmdem(
      "run again.toml -o again.h5 --summary again.json --set effects.mechanics=\"settle\" "
      "--set simulation.duration=0.1", dir);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const auto summary = read_summary(dir + "/again.json");
  ASSERT_TRUE(summary.contains("settle")) << summary.dump();
  EXPECT_TRUE(summary["settle"]["at_rest"].get<bool>());
  EXPECT_EQ(summary["settle"]["ended_by"].get<std::string>(), "network");
  EXPECT_LE(summary["settle"]["steps"].get<int>(), 10) << summary["settle"].dump();
  EXPECT_EQ(summary["mechanics"]["unconverged_steps"].get<int>(), 0);
}

// [[import]] overlaps: a column of 6 disks (r = 1 mm) written as another code leaves a bed made
// at a softened modulus, each overlapping the one below and the floor by 3% of the radius.
// Settled at the defaults ("hold") the column stays where the file put it, to round-off; with
// "push_out" the position step removes the overlaps and the top disk rises by the six overlaps
// (0.18 mm); a value outside the two is refused, naming the key and the valid ones.
TEST(E2eImport, OverlapsOfAnImportAreHeldOrPushedOut) {
  const std::string dir = scratch_dir("import_overlaps");
  const double r = 1e-3, overlap = 0.03 * r;
  std::string csv = "x,y,radius\n";
  std::vector<double> y;
  for (int k = 0; k < 6; ++k) {
    y.push_back(r - overlap + k * (2 * r - overlap));
    char line[96];
    std::snprintf(line, sizeof line, "0.01,%.17g,0.001\n", y.back());
    csv += line;
  }
  write_file(dir + "/column.csv", csv);
  auto settle = [&](const std::string& keys, const std::string& name) {
    write_file(dir + "/" + name + ".toml", imported_bed("file = \"column.csv\"\nmaterial = \"copper\"\ntemperature = 293.15\noverlap_tolerance = 0.05\n" + keys));
    return run_tmdem("run " + name + ".toml -o " + name + ".h5 --summary " + name +
                     ".json --set effects.mechanics=\"settle\" --set simulation.duration=0.05", dir);
  };
  auto top_rise = [&](const std::string& name) {
    const H5::H5File f(dir + "/" + name + ".h5", H5F_ACC_RDONLY);
    std::vector<hsize_t> dims;
    const auto position = read_doubles(f, "/frames/position", &dims);
    double largest = 0.0;
    for (int k = 0; k < 6; ++k) largest = std::max(largest, std::abs(position[3 * k + 1] - y[k]));
    return std::pair{position[3 * 5 + 1] - y[5], largest};
  };
  const auto held = settle("", "held");
  ASSERT_EQ(held.exit_code, 0) << held.output;
  EXPECT_NE(held.output.find("overlaps = \"hold\""), std::string::npos) << held.output;
  EXPECT_LT(top_rise("held").second, 1e-9 * r);
  const auto pushed = settle("overlaps = \"push_out\"", "pushed");
  ASSERT_EQ(pushed.exit_code, 0) << pushed.output;
  EXPECT_NEAR(top_rise("pushed").first, 6 * overlap, 0.05 * 6 * overlap);
  const auto refused = settle("overlaps = \"keep\"", "refused");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.output.find("import[0].overlaps"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("push_out"), std::string::npos) << refused.output;
}

}  // namespace
}  // namespace tmdem::e2e
