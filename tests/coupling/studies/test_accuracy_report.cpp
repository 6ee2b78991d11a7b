// The accuracy study's output: CSV layout, target search, explicit projection, and the example
// scenes of examples/accuracy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "coupling/studies/AccuracyReport.h"
#include "coupling/studies/AccuracyStudy.h"
#include "coupling/bridge/ContactList.h"
#include "coupling/output/ProgressReporter.h"
#include "coupling/scene/SceneLoader.h"
#include "coupling/bridge/ThermalDiagnostics.h"
#include "coupling/run/ThermalProblem.h"

namespace tmdem::coupling {
namespace {

AccuracyRun make_run(const std::string& method, const std::string& solver, double parameter,
                     double error, double wall, long steps, bool ok = true) {
  AccuracyRun r;
  r.method = method;
  r.linear_solver = solver;
  r.parameter = parameter;
  r.max_error_K = error;
  r.wall_time_s = wall;
  r.steps = steps;
  r.rhs_evals = steps;
  r.timings = 1;
  r.ok = ok;
  if (!ok) r.message = "solver failed";
  return r;
}

std::vector<AccuracyRun> sample_runs() {
  return {make_run("explicit", "none", 0.4, 4e-2, 0.001, 250),
          make_run("explicit", "none", 0.1, 1e-2, 0.004, 1000),
          make_run("cvode", "klu", 1e-2, 5e-1, 1e-4, 20),
          make_run("cvode", "klu", 1e-4, 8e-4, 3e-4, 60),
          make_run("cvode", "klu", 1e-6, 9e-7, 9e-4, 200),
          make_run("cvode", "pcg", 1e-6, 0.0, 0.0, 0, false)};
}

// A run the study skipped as predicted too slow, with its prediction.
AccuracyRun skipped_run(const std::string& method, const std::string& solver, double parameter,
                        double predicted_s) {
  AccuracyRun r = make_run(method, solver, parameter, 0.0, 0.0, 0, false);
  r.skipped = true;
  r.predicted_wall_time_s = predicted_s;
  r.message = "predicted " + std::to_string(predicted_s) + " s, over the budget";
  return r;
}

TEST(AccuracyReport, CsvHasContractHeaderExtendedAndNoFailedRun) {
  auto runs = sample_runs();
  runs[2].predicted_wall_time_s = 2.5e-4;
  std::ostringstream out;
  write_accuracy_csv(out, runs);
  const std::string text = out.str();
  // The contract's seven columns, in their places, then the extension's two.
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "method,linear_solver,parameter,max_error_K,wall_time_s,steps,rhs_evals,"
            "status,predicted_wall_time_s");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 6);  // header + 5 successful runs
  EXPECT_NE(text.find("explicit,none,0.4,0.04,0.001,250,250,ok,\n"), std::string::npos) << text;
  EXPECT_NE(text.find("cvode,klu,0.01,0.5,1e-04,20,20,ok,0.00025\n"), std::string::npos) << text;
  EXPECT_NE(text.find("cvode,klu,1e-06,9e-07,9e-04,200,200,ok,\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("pcg"), std::string::npos);
  EXPECT_EQ(text.find("nan"), std::string::npos);
}

// Skipped runs are not runs made: the study's table has no row for them (every row of the
// contract's seven columns is numbers), and the skipped runs' own CSV lists them with their
// prediction and the reason, quoted.
TEST(AccuracyReport, SkippedRunsGoToTheirOwnCsvWithTheirPrediction) {
  auto runs = sample_runs();
  runs.push_back(skipped_run("ida", "klu", 1e-4, 90.5));
  runs.push_back(skipped_run("explicit", "none", 1e-5, std::nan("")));
  runs.back().message = "over the \"work\" budget, 1e12 steps";
  std::ostringstream table;
  write_accuracy_csv(table, runs);
  const std::string made = table.str();
  EXPECT_EQ(std::count(made.begin(), made.end(), '\n'), 6);  // header + 5 made
  EXPECT_EQ(made.find("skipped"), std::string::npos) << made;
  EXPECT_EQ(made.find(",,"), std::string::npos) << made;
  std::ostringstream skipped;
  write_skipped_runs_csv(skipped, runs);
  const std::string text = skipped.str();
  EXPECT_EQ(text.substr(0, text.find('\n')), "method,linear_solver,parameter,predicted_wall_time_s,reason");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;  // header + 2 skipped
  EXPECT_NE(text.find("\nida,klu,1e-04,90.5,\"predicted 90.5"), std::string::npos) << text;
  EXPECT_NE(text.find("\nexplicit,none,1e-05,,\"over the \"\"work\"\" budget, 1e12 steps\"\n"),
            std::string::npos) << text;
  EXPECT_EQ(text.find("nan"), std::string::npos);
  // Skipped runs never count as reaching a target, nor as failures.
  EXPECT_EQ(cheapest_reaching(runs, "ida/klu", 1e9), nullptr);
  EXPECT_FALSE(runs[runs.size() - 2].failed());
  // Nothing skipped: the header alone.
  std::ostringstream none;
  write_skipped_runs_csv(none, sample_runs());
  EXPECT_EQ(none.str(), "method,linear_solver,parameter,predicted_wall_time_s,reason\n");
  EXPECT_EQ(skipped_runs_csv_path("out/study.csv"), "out/study.skipped.csv");
  EXPECT_EQ(skipped_runs_csv_path("study.txt"), "study.txt.skipped.csv");
}

TEST(AccuracyReport, CheapestRunReachingATarget) {
  const auto runs = sample_runs();
  const auto* r = cheapest_reaching(runs, "cvode/klu", 1e-3);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->parameter, 1e-4);
  EXPECT_EQ(cheapest_reaching(runs, "cvode/klu", 1e-6)->parameter, 1e-6);
  EXPECT_EQ(cheapest_reaching(runs, "explicit", 1e-3), nullptr);
  EXPECT_EQ(cheapest_reaching(runs, "cvode/pcg", 1.0), nullptr);  // failed runs never count
}

TEST(AccuracyReport, ExplicitProjectionIsFirstOrder) {
  const auto p = project_explicit(sample_runs(), 100.0, 1e-6);
  ASSERT_TRUE(p.available);
  EXPECT_NEAR(p.observed_order, 1.0, 1e-12);
  EXPECT_NEAR(p.error_constant_K_per_s, 0.1, 1e-15);          // 1e-2 K / 0.1 s
  EXPECT_NEAR(p.step_s, 1e-5, 1e-18);
  EXPECT_NEAR(p.steps, 1e7, 1e-6);
  EXPECT_NEAR(p.wall_time_s, 4e-6 * 1e7, 1e-9);                // 4 us per step
}

TEST(AccuracyReport, ReportNamesReferenceTargetsAndFailures) {
  AccuracyStudyResult res;
  res.end_time_s = 100.0;
  res.nodes = 3;
  res.reference.description = "exact matrix exponential";
  res.runs = sample_runs();
  std::ostringstream out;
  print_accuracy_report(out, res, AccuracyStudyOptions{});
  const std::string text = out.str();
  EXPECT_NE(text.find("exact matrix exponential"), std::string::npos);
  EXPECT_NE(text.find("max error <= 1e-03 K"), std::string::npos) << text;
  EXPECT_NE(text.find("max error <= 1e-06 K"), std::string::npos) << text;
  EXPECT_NE(text.find("FAILED: solver failed"), std::string::npos) << text;
  EXPECT_NE(text.find("projected"), std::string::npos) << text;
  EXPECT_NE(text.find("faster than explicit"), std::string::npos) << text;
}

TEST(AccuracyReport, ReportShowsASkippedMethodsPredictedCost) {
  AccuracyStudyResult res;
  res.end_time_s = 100.0;
  res.reference.description = "exact matrix exponential";
  res.runs = sample_runs();
  res.runs.push_back(skipped_run("ida", "klu", 1e-2, 90.5));
  std::ostringstream out;
  print_accuracy_report(out, res, AccuracyStudyOptions{});
  const std::string text = out.str();
  EXPECT_NE(text.find("skipped: predicted 90.5"), std::string::npos) << text;
  EXPECT_NE(text.find("ida/klu: not reached; skipped from rtol = 1e-02 on (predicted 90.5 s)"),
            std::string::npos)
      << text;
}

TEST(AccuracyExamples, StiffBedIsStiffAndTriangleIsValid) {
  const auto dir = std::filesystem::path(TMDEM_SOURCE_DIR) / "examples" / "accuracy";
  const Scene bed = load_scene_file((dir / "stiff_bed.toml").string());
  EXPECT_GE(bed.particles.size(), 200u);
  EXPECT_LE(bed.particles.size(), 2000u);
  std::ostringstream quiet;
  ProgressReporter progress(quiet, true, false);
  const auto problem = build_frozen_thermal_problem(bed, progress);
  const auto d = diagnose(bed, problem.contacts, *problem.system, max_scene_temperature_K(bed));
  EXPECT_GE(d.max_time_constant_s / d.min_time_constant_s, 1e3);
  const Scene triangle = load_scene_file((dir / "triangle.toml").string());
  EXPECT_EQ(triangle.particles.size(), 14u);
}

}  // namespace
}  // namespace tmdem::coupling
