// End to end: `tmdem run --step-log FILE` writes one CSV line per mechanics step (docs/step-log.md):
// a free fall's lines carry its exact clock and speeds, the lines of a dynamic run add up to the
// summary's totals (retried steps included), a restart appends, and a path that would overwrite
// another of the run's files, or cannot be written, is refused before the run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "E2eSupport.h"
#include "coupling/run/MechanicsStepLog.h"

using namespace tmdem::e2e;

namespace {

struct StepLog {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  double number(std::size_t row, const std::string& column) const { return std::stod(rows.at(row).at(column)); }
};

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

StepLog read_step_log(const std::string& path) {
  StepLog log;
  std::istringstream in(text_of(path));
  std::string line;
  std::getline(in, line);
  log.header = split_csv(line);
  while (std::getline(in, line)) {
    const auto fields = split_csv(line);
    EXPECT_EQ(fields.size(), log.header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < fields.size() && k < log.header.size(); ++k) row[log.header[k]] = fields[k];
    log.rows.push_back(row);
  }
  return log;
}

std::vector<std::string> documented_columns() {
  std::vector<std::string> names;
  for (const auto& c : tmdem::coupling::MechanicsStepLog::columns()) names.push_back(c.name);
  return names;
}

// Copper disks dropped onto a floor between two side walls (a dynamic run: contacts close).
std::string drop_scene(double duration_s) {
  const TomlKeys in_copper = {{"material", "copper"}};
  return copper_drop_scene(duration_s)
      .add("generate", random_fill(12, "{ min = [0.0005, 0.0005, 0.0], max = [0.008, 0.012, 0.0] }",
                                   {{"radius", 0.0008}, {"material", "copper"}, {"temperature", 293.15}}))
      .add("wall", floor_wall(with(in_copper, {{"temperature", 400.0}})))
      .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, in_copper))
      .add("wall", plane_wall({0.0085, 0.0, 0.0}, {-1.0, 0.0, 0.0}, in_copper))
      .set(output("drop.h5", 0.02))
      .str();
}

}  // namespace

TEST(EndToEndStepLog, AFreeFallsLinesCarryItsClockAndItsExactSpeeds) {
  const auto dir = scratch_dir("step_log_fall");
  // Free fall all along: after k steps of h = 1 ms the speed is k h g exactly.
  write_file(dir + "/s.toml", falling_sphere_scene());
  const auto r = run_tmdem("run s.toml --quiet --step-log steps.csv --summary s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto log = read_step_log(dir + "/steps.csv");
  EXPECT_EQ(log.header, documented_columns());
  ASSERT_EQ(log.rows.size(), 10u);
  for (std::size_t k = 0; k < log.rows.size(); ++k) {
    EXPECT_EQ(log.rows[k].at("phase"), "settle");
    EXPECT_NEAR(log.number(k, "t_s"), double(k + 1) * 1e-3, 1e-15);
    EXPECT_EQ(log.number(k, "h_s"), 1e-3);
    EXPECT_NEAR(log.number(k, "max_speed_m_per_s"), double(k + 1) * 1e-3 * 9.81, 1e-12);
    EXPECT_EQ(log.rows[k].at("converged"), "1");
    EXPECT_EQ(log.rows[k].at("active_contacts"), "0");
  }
}

TEST(EndToEndStepLog, ADynamicRunsLinesAddUpToTheSummaryRetriesIncluded) {
  const auto dir = scratch_dir("step_log_drop");
  write_file(dir + "/drop.toml", drop_scene(0.1));
  // As built, and with a sweep budget too short for the landings' tolerance: those steps end
  // unconverged and are retaken in parts, whose sweeps the lines must still carry.
  for (const std::string budget : {"", " --set mechanics.max_iterations=12 --set mechanics.tolerance=1e-9"}) {
    const auto r = run_tmdem("run drop.toml --quiet --overwrite --step-log steps.csv --summary s.json" + budget, dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto s = read_summary(dir + "/s.json");
    const auto log = read_step_log(dir + "/steps.csv");
    ASSERT_EQ(log.rows.size(), 100u) << budget;  // 0.1 s of 1 ms steps, each one line
    double sweeps = 0.0, max_siconos = 0.0;
    long unconverged = 0, retried = 0;
    for (std::size_t k = 0; k < log.rows.size(); ++k) {
      EXPECT_EQ(log.rows[k].at("phase"), "run");
      EXPECT_NEAR(log.number(k, "t_s"), double(k + 1) * 1e-3, 1e-12);
      sweeps += log.number(k, "sweeps");
      max_siconos = std::max(max_siconos, log.number(k, "siconos_residual"));
      unconverged += log.rows[k].at("converged") == "0";
      retried += log.number(k, "retry_parts") > 0;
    }
    const auto& m = s["mechanics"];
    EXPECT_NEAR(sweeps, m["mean_iterations"].get<double>() * m["steps"].get<double>(), 1e-6 * sweeps) << budget;
    EXPECT_EQ(unconverged, m["unconverged_time_steps"].get<long>()) << budget;
    EXPECT_EQ(retried, m["retried_steps"].get<long>()) << budget;
    EXPECT_NEAR(max_siconos, m["max_siconos_residual"].get<double>(), 1e-3 * max_siconos) << budget;
    if (!budget.empty()) {
      EXPECT_GT(retried, 0) << "the short budget was meant to make steps be retaken";
      EXPECT_GT(m["steps"].get<long>(), 100) << "a retaken step's parts count in the summary's steps";
    }
  }
}

TEST(EndToEndStepLog, ARestartAppendsItsSteps) {
  const auto dir = scratch_dir("step_log_restart");
  write_file(dir + "/drop.toml", drop_scene(0.1));
  // Stopped at 0.05 s, where it writes its checkpoint, then continued to 0.1 s from it.
  auto r = run_tmdem("run drop.toml --quiet --step-log steps.csv --set simulation.duration=0.05 "
                     "--set output.checkpoint_interval=0.05", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(dir + "/drop.checkpoint.h5"));
  r = run_tmdem("run drop.toml --quiet --step-log steps.csv --restart drop.checkpoint.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto log = read_step_log(dir + "/steps.csv");
  EXPECT_EQ(log.header, documented_columns());  // one header: the restart appended below it
  ASSERT_EQ(log.rows.size(), 100u);
  for (std::size_t k = 0; k < log.rows.size(); ++k)
    EXPECT_NEAR(log.number(k, "t_s"), double(k + 1) * 1e-3, 1e-12) << k;
}

TEST(EndToEndStepLog, APathThatIsAnotherOfTheRunsFilesOrCannotBeWrittenIsRefusedBeforeTheRun) {
  const auto dir = scratch_dir("step_log_refused");
  write_file(dir + "/drop.toml", drop_scene(0.01));
  const std::string scene_text = text_of(dir + "/drop.toml");
  for (const std::string path : {"drop.toml", "drop.h5", "s.json"}) {
    const auto r = run_tmdem("run drop.toml --quiet --summary s.json --step-log " + path, dir);
    EXPECT_EQ(r.exit_code, 2) << path << ": " << r.output;
    EXPECT_NE(r.output.find("step log '" + path + "'"), std::string::npos) << r.output;
  }
  EXPECT_EQ(text_of(dir + "/drop.toml"), scene_text);
  const auto r = run_tmdem("run drop.toml --quiet --step-log no_such_folder/steps.csv", dir);
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot write step log 'no_such_folder/steps.csv': folder 'no_such_folder' does not exist"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/drop.h5"));
}

TEST(StepLogReference, DocsStepLogMdIsTheGeneratedReference) {
  const std::string committed = text_of(std::string(TMDEM_SOURCE_DIR) + "/docs/step-log.md");
  EXPECT_TRUE(committed == tmdem::coupling::MechanicsStepLog::reference_markdown())
      << "docs/step-log.md differs from the columns the log writes; regenerate it with:\n"
         "  build/tmdem docs step-log > docs/step-log.md";
}

// `tmdem study conductivity --pressures` logs each load's settle as its own phase, its clock
// from 0; a step log that is the study's CSV is refused.
TEST(EndToEndStepLog, APressureStudyLogsEachLoadsSettle) {
  const auto dir = scratch_dir("step_log_study");
  write_file(dir + "/bed.toml",
             SceneBuilder()
                 .set("simulation.duration", 1.0)
                 .add("material", steel({{"friction", 0.0}}))
                 .set({{"effects.mechanics", "settle"}, {"mechanics.tolerance", 1e-10}})
                 .add("generate", lattice({2, 3, 2}))
                 .add("wall", floor_wall({{"temperature", 310.0}}))
                 .add("wall", plane_wall({0.0, 0.006, 0.0}, {0.0, -1.0, 0.0},
                                         {{"temperature", 290.0}, {"piston", true}, {"mass", 1e-3}}))
                 .add("wall", plane_wall({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}))
                 .add("wall", plane_wall({0.004, 0.0, 0.0}, {-1.0, 0.0, 0.0}))
                 .str());
  auto r = run_tmdem("study conductivity bed.toml --pressures 1e3,1e4 --quiet --step-log steps.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto log = read_step_log(dir + "/steps.csv");
  EXPECT_EQ(log.header, documented_columns());
  ASSERT_FALSE(log.rows.empty());
  std::vector<std::string> phases;
  for (std::size_t k = 0; k < log.rows.size(); ++k) {
    const std::string& phase = log.rows[k].at("phase");
    if (phases.empty() || phases.back() != phase) {
      phases.push_back(phase);
      EXPECT_NEAR(log.number(k, "t_s"), log.number(k, "h_s"), 1e-15) << phase << ": its clock starts at 0";
    }
  }
  EXPECT_EQ(phases, (std::vector<std::string>{"settle at 1000 Pa", "settle at 10000 Pa"}));
  r = run_tmdem("study conductivity bed.toml --pressures 1e3 --quiet --csv k.csv --step-log k.csv", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("step log 'k.csv' is the CSV file"), std::string::npos) << r.output;
}
