// thermal.linear_solver = "auto": the rule of coupling/run/LinearSolverChoice.h branch by branch
// (explicit choices kept, MPI, one-sided Jacobians, the size thresholds in 3D and 2D), the
// scene-level resolution on a real thermal system, the MPI refusal, tmdem check's KLU warning,
// and whole runs whose summaries name the resolved solver and why.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "coupling/bridge/ContactList.h"
#include "coupling/run/DistributedHeating.h"
#include "coupling/run/LinearSolverChoice.h"
#include "coupling/run/ThermalProblem.h"
#include "coupling/scene/SceneLoader.h"
#include "support/RunSceneText.h"
#include "support/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

using namespace tmdem::test;
using thermal::LinearSolverKind;

// `requested` as the scene names it ("auto": none).
LinearSolverChoice choose(const std::string& requested, std::size_t particles, int dimension = 3,
                          int processes = 1, bool symmetric = true) {
  std::optional<LinearSolverKind> kind;
  if (requested != "auto") kind = thermal::parse_linear_solver_kind(requested);
  return choose_linear_solver({kind, particles, dimension, processes, symmetric});
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(LinearSolverChoice, AutoTakesKluBelowTheThresholdAndPcgFromIt) {
  const auto small = choose("auto", kKluParticles3d - 1);
  EXPECT_EQ(small.kind, LinearSolverKind::Klu);
  EXPECT_TRUE(small.automatic);
  EXPECT_EQ(small.reason, "auto: 4999 particles < 5000 in 3D");
  const auto large = choose("auto", 25000);
  EXPECT_EQ(large.kind, LinearSolverKind::Pcg);
  EXPECT_EQ(large.reason, "auto: 25000 particles >= 5000 in 3D, symmetric Jacobian");
  EXPECT_EQ(choose("auto", kKluParticles3d).kind, LinearSolverKind::Pcg);
  EXPECT_EQ(choose("auto", 0).kind, LinearSolverKind::Klu);
}

TEST(LinearSolverChoice, TwoDimensionalBedsKeepKluTenTimesLonger) {
  // 2D fill-in grows gently (measured: KLU 2-8 s at 10^5 particles where 3D took 121 s at
  // 4.7 x 10^4): the same 25,000 particles keep KLU in 2D.
  EXPECT_EQ(choose("auto", 25000, 2).kind, LinearSolverKind::Klu);
  EXPECT_EQ(choose("auto", kKluParticles2d - 1, 2).kind, LinearSolverKind::Klu);
  const auto large = choose("auto", kKluParticles2d, 2);
  EXPECT_EQ(large.kind, LinearSolverKind::Pcg);
  EXPECT_EQ(large.reason, "auto: 50000 particles >= 50000 in 2D, symmetric Jacobian");
}

TEST(LinearSolverChoice, TheLargestBedsTakeAmg) {
  EXPECT_EQ(choose("auto", kAmgParticles - 1).kind, LinearSolverKind::Pcg);
  const auto huge = choose("auto", kAmgParticles);
  EXPECT_EQ(huge.kind, LinearSolverKind::Amg);
  EXPECT_TRUE(contains(huge.reason, "particles >= " + std::to_string(kAmgParticles)));
  EXPECT_EQ(choose("auto", 1'000'000, 2).kind, LinearSolverKind::Amg);
}

TEST(LinearSolverChoice, OneSidedJacobiansTakeKluWhateverTheSize) {
  for (const std::size_t n : {std::size_t(10), std::size_t(25000), std::size_t(2'000'000)}) {
    const auto c = choose("auto", n, 3, 1, false);
    EXPECT_EQ(c.kind, LinearSolverKind::Klu) << n;
    EXPECT_TRUE(contains(c.reason, "one-sided Jacobian")) << c.reason;
  }
}

TEST(LinearSolverChoice, SeveralProcessesTakeAmgWhateverTheSize) {
  for (const std::size_t n : {std::size_t(10), std::size_t(25000)}) {
    const auto c = choose("auto", n, 3, 2);
    EXPECT_EQ(c.kind, LinearSolverKind::Amg) << n;
    EXPECT_EQ(c.reason, "auto: heating over 2 MPI processes, which only amg spans");
  }
  // Before the symmetry test: the MPI integrator refuses a one-sided Jacobian itself, naming it.
  EXPECT_EQ(choose("auto", 100, 3, 4, false).kind, LinearSolverKind::Amg);
}

TEST(LinearSolverChoice, ExplicitChoicesAreKeptExactlyAndOverMpiOnlyAmg) {
  // Whatever the size, dimension, processes or symmetry: the rule only ever fills in "auto";
  // over several processes it refuses klu and pcg (the MPI integrator is always amg).
  for (const auto kind : {LinearSolverKind::Klu, LinearSolverKind::Pcg, LinearSolverKind::Amg}) {
    const std::string name(thermal::name_of(kind));
    for (const std::size_t n : {std::size_t(10), std::size_t(1'000'000)})
      for (const int processes : {1, 3})
        for (const bool symmetric : {true, false}) {
          const auto c = choose(name, n, 3, processes, symmetric);
          EXPECT_EQ(c.kind, kind) << name << " " << n << " " << processes << " " << symmetric;
          EXPECT_FALSE(c.automatic);
          EXPECT_EQ(c.reason, "explicit: thermal.linear_solver = \"" + name + "\"");
          const bool refused = processes > 1 && kind != LinearSolverKind::Amg;
          EXPECT_EQ(c.refusal.empty(), !refused) << name << " " << processes << ": " << c.refusal;
          if (refused) {
            EXPECT_EQ(c.refusal, "thermal.linear_solver = \"" + name +
                                     "\" runs in one process only; use \"amg\" (conjugate "
                                     "gradients with BoomerAMG across the processes)");
          }
        }
  }
  // "auto" is never refused: over MPI it is amg.
  EXPECT_EQ(choose("auto", 10, 3, 2).refusal, "");
}

// The rule's numbers are stated in the docs; a change of one must change them too.
TEST(LinearSolverChoice, TheDocsStateTheThresholds) {
  std::ifstream in(std::string(TMDEM_SOURCE_DIR) + "/docs/integrators.md");
  ASSERT_TRUE(in);
  std::stringstream text;
  text << in.rdbuf();
  for (const char* figure : {"5,000", "50,000", "500,000"})
    EXPECT_TRUE(contains(text.str(), figure)) << figure << " is not in docs/integrators.md";
}

// A steel lattice, mechanics off, constant conductance, corner particle 0 at 373.15 K, 2 s.
SceneBuilder lattice_scene(std::initializer_list<int> counts) {
  return thermal_scene()
      .set("simulation.duration", 2.0)
      .set(output("out.h5", 2.0))
      .set("output.contacts", false)
      .add("generate", lattice(counts))
      .add("assign", assign_ids({0}, {{"temperature", 373.15}}));
}

TEST(LinearSolverChoice, ASceneIsResolvedOnItsThermalSystem) {
  auto resolve = [](const std::string& text) {
    const auto scene = load_scene_text(text, "choice");
    ContactList contacts;
    const auto system = build_thermal_system(scene, contacts);
    return choose_linear_solver(scene, *system, 1);
  };
  const auto small = resolve(lattice_scene({3, 3, 2}).str());
  EXPECT_EQ(small.kind, LinearSolverKind::Klu);
  EXPECT_EQ(small.reason, "auto: 18 particles < 5000 in 3D");
  // A conductivity table makes the Jacobian one-sided.
  const auto table = resolve(lattice_scene({3, 3, 2})
                                 .set("material[0].conductivity",
                                      raw("[[250.0, 60.0], [500.0, 40.0]]"))
                                 .str());
  EXPECT_EQ(table.kind, LinearSolverKind::Klu);
  EXPECT_TRUE(contains(table.reason, "one-sided")) << table.reason;
  const auto explicit_pcg =
      resolve(lattice_scene({3, 3, 2}).set("thermal.linear_solver", "pcg").str());
  EXPECT_EQ(explicit_pcg.kind, LinearSolverKind::Pcg);
  EXPECT_FALSE(explicit_pcg.automatic);
}

TEST(LinearSolverChoice, UnderMpiTheDefaultIsAcceptedAndKluRefused) {
  const auto scene = load_scene_text(lattice_scene({3, 3, 2}).str(), "mpi");
  EXPECT_FALSE(scene.thermal.linear_solver.has_value());  // "auto"
  EXPECT_EQ(distributed_heating_refusal(scene, 2), "");
  auto klu = scene;
  klu.thermal.linear_solver = LinearSolverKind::Klu;
  const auto why = distributed_heating_refusal(klu, 2);
  EXPECT_TRUE(contains(why, "thermal.linear_solver = \"klu\" runs in one process only")) << why;
  EXPECT_TRUE(contains(why, "\"amg\"")) << why;
}

TEST(LinearSolverChoice, CheckWarnsOfAnExplicitKluOnALarge3dBed) {
  const auto warning = klu_size_warning({LinearSolverKind::Klu, 25000, 3, 1, true});
  EXPECT_TRUE(contains(warning, "KLU's fill on a 3D network this size")) << warning;
  EXPECT_TRUE(contains(warning, "\"pcg\" or \"amg\"")) << warning;
  EXPECT_TRUE(contains(klu_size_warning({LinearSolverKind::Klu, 25000, 3, 1, false}), "one-sided"));
  EXPECT_EQ(klu_size_warning({LinearSolverKind::Klu, kKluParticles3d - 1, 3, 1, true}), "");
  EXPECT_EQ(klu_size_warning({LinearSolverKind::Klu, 25000, 2, 1, true}), "");   // 2D: KLU's fill stays small
  EXPECT_EQ(klu_size_warning({std::nullopt, 25000, 3, 1, true}), "");  // auto takes pcg there
  EXPECT_EQ(klu_size_warning({LinearSolverKind::Pcg, 25000, 3, 1, true}), "");
}

// Whole runs: the summary names the solver the run used and why.
TEST(LinearSolverChoice, ASmallRunAtTheDefaultUsesKlu) {
  const auto outcome = run_scene_text(lattice_scene({3, 3, 2}).str(), "choice_default");
  ASSERT_EQ(outcome.exit_code, 0) << outcome.summary.message;
  EXPECT_EQ(outcome.summary.thermal.linear_solver, "klu");
  EXPECT_EQ(outcome.summary.thermal.linear_solver_reason, "auto: 18 particles < 5000 in 3D");
  const auto json = outcome.summary.to_json();
  EXPECT_EQ(json["thermal"]["linear_solver"], "klu");
  EXPECT_EQ(json["thermal"]["linear_solver_reason"], "auto: 18 particles < 5000 in 3D");
}

TEST(LinearSolverChoice, TheDefaultIsTheSameBitsAsAnExplicitKlu) {
  const auto automatic = run_scene_text(lattice_scene({3, 3, 2}).str(), "choice_auto");
  const auto klu = run_scene_text(
      lattice_scene({3, 3, 2}).set("thermal.linear_solver", "klu").str(), "choice_klu");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.summary.message;
  ASSERT_EQ(klu.exit_code, 0) << klu.summary.message;
  EXPECT_EQ(automatic.final_temperature_K, klu.final_temperature_K);
  EXPECT_EQ(klu.summary.thermal.linear_solver_reason, "explicit: thermal.linear_solver = \"klu\"");
}

TEST(LinearSolverChoice, ALargeRunAtTheDefaultUsesPcg) {
  // 5,000 particles (50 x 10 x 10): the first size that leaves KLU in 3D; 0.02 s of pcg.
  const auto outcome = run_scene_text(lattice_scene({50, 10, 10}).str(), "choice_large");
  ASSERT_EQ(outcome.exit_code, 0) << outcome.summary.message;
  EXPECT_EQ(outcome.summary.particles, 5000);
  EXPECT_EQ(outcome.summary.thermal.linear_solver, "pcg");
  EXPECT_EQ(outcome.summary.thermal.linear_solver_reason,
            "auto: 5000 particles >= 5000 in 3D, symmetric Jacobian");
  EXPECT_GT(outcome.final_temperature_K[0], 293.15);
  EXPECT_LT(outcome.final_temperature_K[0], 373.15);  // heat left the hot corner
}

}  // namespace
}  // namespace tmdem::coupling
