// Heating over MPI (docs/scale-out.md): `mpirun -np 2 tmdem run` on a frozen bed gives the
// temperatures of the one-process run to the integrator's tolerance, closes its energy balance
// to round-off, and refuses what it cannot split. Skipped when mpirun is not installed or cannot
// start two processes here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "E2eSupport.h"
#include "ResultComparison.h"

namespace tmdem::e2e {
namespace {

constexpr double kRelativeTolerance = 1e-6;
constexpr double kAbsoluteTolerance_K = 1e-6;

struct BedShape {
  std::string mechanics = "off";
  std::string counts = "[10, 6, 6]";
  double lid_z_m = 0.012;   // on the top layer
  int held_id = 300;
  std::string gravity = "[0.0, 0.0, 0.0]";
  std::string periodic;  // a [periodic] table, or none
  bool contacts = true;  // output.contacts; false: each process builds only its piece of the bed
};

// Steel spheres touching in a lattice on a hot floor under a cooled flux lid, convection, a
// source, a held particle. The slabs cut across the longest extent: a 10 x 6 x 6 bed across x
// (each process has particles on the floor and under the lid), a 4 x 4 x 20 column across z.
std::string lattice_bed_scene(const BedShape& shape) {
  return R"(format = "tmdem-scene-1"
[simulation]
duration = 20.0
dimension = 3
gravity = )" + shape.gravity + R"(
)" + shape.periodic + R"(
[effects]
mechanics = ")" + shape.mechanics + R"("
convection = true
[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
conductivity = 50.0
heat_capacity = 460.0
[[generate]]
kind = "lattice"
counts = )" + shape.counts + R"(
spacing = 0.002
radius = 0.001
origin = [0.001, 0.001, 0.001]
material = "steel"
temperature = 293.15
[[assign]]
ids = [17]
heat_source = 0.05
[[assign]]
ids = [)" + std::to_string(shape.held_id) + R"(]
temperature = 330.0
fixed_temperature = true
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "steel"
temperature = 400.0
[[wall]]
point = [0.0, 0.0, )" + std::to_string(shape.lid_z_m) + R"(]
normal = [0.0, 0.0, -1.0]
material = "steel"
heat_flux = -2000.0
heat_flux_area = 2.4e-4
[convection]
coefficient = 20.0
[thermal]
integrator = "cvode"
linear_solver = "amg"
conductance = "constant"
constant_conductance = 1.0e-3
relative_tolerance = )" + std::to_string(kRelativeTolerance) + R"(
absolute_tolerance = )" + std::to_string(kAbsoluteTolerance_K) + R"(
[output]
interval = 2.0
contacts = )" + std::string(shape.contacts ? "true" : "false") + R"(
)";
}

// mpirun is installed and can start two processes here (asked once per test program).
bool have_mpirun() {
  static const bool works =
      std::system("command -v mpirun > /dev/null 2>&1 && env OMPI_ALLOW_RUN_AS_ROOT=1 "
                  "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -np 2 --oversubscribe true "
                  "> /dev/null 2>&1") == 0;
  return works;
}

// mpirun -np N tmdem ARGS in workdir (OpenMPI as root needs the two variables; --oversubscribe:
// the machine may have fewer free cores than processes; yield: waiting processes give way).
ProgramResult run_tmdem_mpi(const std::string& args, const std::string& workdir,
                            int processes = 2) {
  return run_tmdem(args, workdir,
                   "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                   "OMPI_MCA_mpi_yield_when_idle=1",
                   "mpirun -np " + std::to_string(processes) + " --oversubscribe");
}

std::vector<double> final_temperatures(const std::string& path, std::size_t& frames) {
  H5::H5File f(path, H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto T = read_doubles(f, "frames/temperature", &dims);
  frames = dims.at(0);
  return {T.end() - std::ptrdiff_t(dims.at(1)), T.end()};
}

// The scene run by one process and by `processes` (T2, s2): final temperatures and summaries.
struct OneAndMany {
  int processes = 2;
  std::vector<double> T1, T2;
  nlohmann::json s1, s2;
  std::string output1, output2;  // what the one-process run and the run over `processes` printed
};

OneAndMany heat_with_one_and_many(const std::string& name, const BedShape& shape,
                                  int processes = 2) {
  const auto dir = scratch_dir(name);
  write_file(dir + "/bed.toml", lattice_bed_scene(shape));
  OneAndMany out;
  out.processes = processes;
  const auto one = run_tmdem("run bed.toml -o one.h5 --summary one.json", dir);
  EXPECT_EQ(one.exit_code, 0) << one.output;
  const auto two = run_tmdem_mpi("run bed.toml -o two.h5 --summary two.json", dir, processes);
  EXPECT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("heating over " + std::to_string(processes) + " MPI processes"),
            std::string::npos)
      << two.output;
  out.output1 = one.output;
  out.output2 = two.output;
  if (one.exit_code != 0 || two.exit_code != 0) return out;
  std::size_t frames_one = 0, frames_two = 0;
  out.T1 = final_temperatures(dir + "/one.h5", frames_one);
  out.T2 = final_temperatures(dir + "/two.h5", frames_two);
  EXPECT_EQ(frames_one, 11u);
  EXPECT_EQ(frames_two, frames_one);
  out.s1 = read_summary(dir + "/one.json");
  out.s2 = read_summary(dir + "/two.json");
  return out;
}

// The two runs differ only in the preconditioner (one V-cycle over one or more processes), which
// moves each step's Newton solution within the linear tolerance: the final temperatures agree to
// the tolerance the integrator keeps on each step, rtol |T| + atol (the hottest is 400 K).
void expect_equal_to_the_tolerance(const OneAndMany& r, std::size_t particles) {
  ASSERT_EQ(r.T1.size(), particles);
  ASSERT_EQ(r.T2.size(), particles);
  double difference_K = 0.0, rise_K = 0.0;
  for (std::size_t i = 0; i < particles; ++i) {
    difference_K = std::max(difference_K, std::abs(r.T2[i] - r.T1[i]));
    rise_K = std::max(rise_K, std::abs(r.T1[i] - 293.15));
  }
  EXPECT_GT(rise_K, 10.0);  // the bed did heat: the comparison means something
  EXPECT_LE(difference_K, kRelativeTolerance * 400.0 + kAbsoluteTolerance_K) << difference_K;
  EXPECT_EQ(r.s2["status"], "ok");
  EXPECT_EQ(r.s2["particles"], std::int64_t(particles));
  EXPECT_EQ(r.s2["mpi"]["processes"], r.processes);
  EXPECT_FALSE(r.s1.contains("mpi"));
  // Energy: with conjugate gradients each Newton solve stops at the linear tolerance, which
  // leaves the balance at ~1e-11 in one process too (2.6e-11 for the frozen bed); two processes
  // do no worse.
  EXPECT_LT(std::abs(r.s2["energy"]["balance_error_rel"].get<double>()), 1e-10);
  for (const char* key : {"final_J", "boundary_heat_J"})
    EXPECT_NEAR(r.s2["energy"][key].get<double>(), r.s1["energy"][key].get<double>(),
                kRelativeTolerance * std::abs(r.s1["energy"][key].get<double>()))
        << key;
}

TEST(E2eMpi, TwoProcessesHeatAFrozenBedAsOneToTheIntegratorTolerance) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  const auto r = heat_with_one_and_many("mpi_frozen", BedShape{});
  expect_equal_to_the_tolerance(r, 360);
  if (r.T2.empty()) return;
  EXPECT_DOUBLE_EQ(r.T2[300], 330.0);  // held
  EXPECT_EQ(r.s2["mpi"]["ghosts"], 72);  // the cut at x = 10 mm: 6 x 6 particles on each side
}

// Three slabs: the middle process exchanges ghosts with two neighbours.
TEST(E2eMpi, ThreeProcessesHeatAFrozenBedAsOne) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  expect_equal_to_the_tolerance(heat_with_one_and_many("mpi_three", BedShape{}, 3), 360);
}

// Periodic along x (20 mm: the lattice's first and last columns touch round the boundary): the
// first and the last of three slabs exchange ghosts too, the network's edges round the boundary.
TEST(E2eMpi, ThreeProcessesHeatAPeriodicBedAsOne) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  BedShape periodic;
  periodic.periodic = "[periodic]\nx = [0.0, 0.02]\n";
  const auto r = heat_with_one_and_many("mpi_periodic", periodic, 3);
  expect_equal_to_the_tolerance(r, 360);
  const auto open = heat_with_one_and_many("mpi_open", BedShape{}, 3);
  if (r.T2.empty() || open.T2.empty()) return;
  // The boundary's 36 pairs: their heat makes the periodic bed's temperatures differ, and their
  // two ends are ghosts of the first and the last process.
  double difference_K = 0.0;
  for (std::size_t i = 0; i < 360; ++i) difference_K = std::max(difference_K, std::abs(r.T1[i] - open.T1[i]));
  EXPECT_GT(difference_K, 0.1);
  EXPECT_EQ(r.s2["mpi"]["ghosts"].get<int>(), open.s2["mpi"]["ghosts"].get<int>() + 72);
}

// Mechanics off and no contacts in the frames: each process detects the contacts of its own
// particles and those within reach of its slab alone and builds only its piece of the network
// (coupling/run/BedPiece.h). The same local networks as when every process builds the whole
// bed, edges in the same order: the same temperatures as that run (to round-off: the flux
// lid's conductance is summed over the processes) and as one process to the tolerance.
TEST(E2eMpi, EachProcessBuildingOnlyItsPieceHeatsAsTheWholeSetUp) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  BedShape pieces;
  pieces.contacts = false;
  const auto r = heat_with_one_and_many("mpi_pieces", pieces);
  expect_equal_to_the_tolerance(r, 360);
  const auto whole = heat_with_one_and_many("mpi_whole", BedShape{});
  if (r.T2.empty() || whole.T2.empty()) return;
  EXPECT_EQ(r.s2["mpi"]["ghosts"], 72);
  double difference_K = 0.0;
  for (std::size_t i = 0; i < 360; ++i) difference_K = std::max(difference_K, std::abs(r.T2[i] - whole.T2[i]));
  EXPECT_LE(difference_K, 1e-10);
  // The start-up diagnostics, combined from the processes' own particles: one process's lines.
  for (const std::string figure : {"heat-carrying contacts", "largest contact Biot number",
                                   "time constants", "explicit stability bound"}) {
    const auto line_of = [&](const std::string& output) {
      const auto at = output.find(figure);
      if (at == std::string::npos) return std::string("(none)");
      const auto start = output.rfind('\n', at) + 1;
      return output.substr(start, output.find('\n', at) - start);
    };
    EXPECT_NE(line_of(r.output1), "(none)") << figure;
    EXPECT_EQ(line_of(r.output2), line_of(r.output1));
  }
}

// The same, periodic across the cut axis over three processes: the first and the last keep
// the particles beyond the boundary in their halo.
TEST(E2eMpi, ThreeProcessesBuildingOnlyTheirPiecesOfAPeriodicBedHeatAsOne) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  BedShape periodic;
  periodic.contacts = false;
  periodic.periodic = "[periodic]\nx = [0.0, 0.02]\n";
  const auto r = heat_with_one_and_many("mpi_periodic_pieces", periodic, 3);
  expect_equal_to_the_tolerance(r, 360);
  EXPECT_EQ(r.s2["mpi"]["ghosts"], 3 * 72);  // three cuts of 6 x 6 pairs, both ends ghosts
}

// Settled first (every process settles the same column and checks that they agree), then
// frozen and split across z: the vertical contacts are cut.
TEST(E2eMpi, TwoProcessesHeatASettledColumnAsOne) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  BedShape column;
  column.mechanics = "settle";
  column.counts = "[4, 4, 20]";
  column.lid_z_m = 0.040;
  column.held_id = 200;
  column.gravity = "[0.0, 0.0, -9.81]";
  const auto r = heat_with_one_and_many("mpi_settled", column);
  expect_equal_to_the_tolerance(r, 320);
  EXPECT_EQ(r.s2["mpi"]["ghosts"], 32);  // 4 x 4 on each side of the cut
  EXPECT_TRUE(r.s2["settle"]["at_rest"].get<bool>());
}

// Checkpoints over MPI: rank 0 writes them from the gathered state, every process restarts from
// one. A run stopped at 8 s and restarted to 20 s gives the uninterrupted run's file and summary
// bit for bit (each checkpoint is an integration boundary in both). Also when each process
// builds only its piece of the bed (no contacts in the frames): the checkpoint then holds no
// contacts, and the restart detects them again.
TEST(E2eMpi, RestartFromACheckpointIsBitForBit) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  for (const bool contacts : {true, false}) {
    SCOPED_TRACE(contacts ? "contacts in the frames" : "pieces");
    const auto dir = scratch_dir(contacts ? "mpi_restart" : "mpi_restart_pieces");
    BedShape shape;
    shape.contacts = contacts;
    write_file(dir + "/bed.toml", lattice_bed_scene(shape));
    const std::string every_4_s = "run bed.toml --set output.checkpoint_interval=4 ";
    const auto whole = run_tmdem_mpi(every_4_s + "-o whole.h5 --summary whole.json", dir);
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    const auto first = run_tmdem_mpi(every_4_s + "--set simulation.duration=8 -o part.h5", dir);
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const auto rest = run_tmdem_mpi(
        every_4_s + "-o part.h5 --restart part.checkpoint.h5 --summary part.json", dir);
    ASSERT_EQ(rest.exit_code, 0) << rest.output;
    std::size_t compared = 0;
    EXPECT_EQ(result_differences(dir + "/whole.h5", dir + "/part.h5", &compared),
              std::vector<std::string>{});
    EXPECT_GT(compared, 10u);
    EXPECT_EQ(summary_without_wall_times(dir + "/whole.json"),
              summary_without_wall_times(dir + "/part.json"));
  }
}

// A scene that names no linear solver ("auto") heats over MPI with amg, and the summary says why;
// an explicit "klu" is still refused, naming the key, its value and the fix.
TEST(E2eMpi, TheDefaultLinearSolverIsAmgAndKluIsRefused) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  const auto dir = scratch_dir("mpi_auto");
  std::string scene = lattice_bed_scene(BedShape{});
  const std::string amg_line = "linear_solver = \"amg\"\n";
  ASSERT_NE(scene.find(amg_line), std::string::npos);
  scene.erase(scene.find(amg_line), amg_line.size());
  write_file(dir + "/bed.toml", scene);
  const auto two = run_tmdem_mpi("run bed.toml -o two.h5 --summary two.json", dir);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("thermal: integrator cvode (amg; auto: heating over 2 MPI processes"),
            std::string::npos)
      << two.output;
  const auto summary = read_summary(dir + "/two.json");
  EXPECT_EQ(summary["thermal"]["linear_solver"], "amg");
  EXPECT_EQ(summary["thermal"]["linear_solver_reason"],
            "auto: heating over 2 MPI processes, which only amg spans");
  const auto klu = run_tmdem_mpi("run bed.toml --set thermal.linear_solver=klu -o klu.h5", dir);
  EXPECT_EQ(klu.exit_code, 2) << klu.output;
  EXPECT_NE(klu.output.find("thermal.linear_solver = \"klu\" runs in one process only; use "
                            "\"amg\""),
            std::string::npos)
      << klu.output;
}

TEST(E2eMpi, OnlyRunRunsOverMpi) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  const auto dir = scratch_dir("mpi_check");
  write_file(dir + "/bed.toml", lattice_bed_scene(BedShape{}));
  const auto check = run_tmdem_mpi("check bed.toml", dir);
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("only `tmdem run` runs over MPI"), std::string::npos) << check.output;
}

TEST(E2eMpi, RefusesAMovingBed) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin) or cannot start 2 processes";
  const auto dir = scratch_dir("mpi_dynamic");
  BedShape moving;
  moving.mechanics = "dynamic";
  write_file(dir + "/bed.toml", lattice_bed_scene(moving));
  const auto two = run_tmdem_mpi("run bed.toml -o two.h5", dir);
  EXPECT_EQ(two.exit_code, 2) << two.output;
  EXPECT_NE(two.output.find("heating over MPI (2 processes): effects.mechanics = \"dynamic\""),
            std::string::npos)
      << two.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/two.h5"));
}

}  // namespace
}  // namespace tmdem::e2e
