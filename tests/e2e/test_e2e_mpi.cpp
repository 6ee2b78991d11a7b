// Heating over MPI (docs/scale-out.md): `mpirun -np 2 tmdem run` on a frozen bed gives the
// temperatures of the one-process run to the integrator's tolerance, closes its energy balance
// to round-off, and refuses what it cannot split. Skipped when mpirun is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "E2eSupport.h"

namespace tmdem::e2e {
namespace {

// 10 x 6 x 6 steel spheres touching in a lattice (x the longest: the slabs cut across x, so each
// process has particles on the hot floor and under the cooled lid), convection, a source, a
// held particle; contacts from geometry (mechanics off).
constexpr double kRelativeTolerance = 1e-6;
constexpr double kAbsoluteTolerance_K = 1e-6;

std::string frozen_bed_scene(const std::string& mechanics) {
  return R"(format = "tmdem-scene-1"
[simulation]
duration = 20.0
dimension = 3
[effects]
mechanics = ")" + mechanics + R"("
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
counts = [10, 6, 6]
spacing = 0.002
radius = 0.001
origin = [0.001, 0.001, 0.001]
material = "steel"
temperature = 293.15
[[assign]]
ids = [17]
heat_source = 0.05
[[assign]]
ids = [300]
temperature = 330.0
fixed_temperature = true
[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "steel"
temperature = 400.0
[[wall]]
point = [0.0, 0.0, 0.012]
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
)";
}

bool have_mpirun() { return std::system("command -v mpirun > /dev/null 2>&1") == 0; }

// mpirun -np 2 tmdem ARGS in workdir (OpenMPI as root needs the two variables; --oversubscribe:
// the machine may have fewer free cores than processes; yield: waiting processes give way).
ProgramResult run_tmdem_mpi(const std::string& args, const std::string& workdir) {
  return run_tmdem(args, workdir,
                   "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                   "OMPI_MCA_mpi_yield_when_idle=1",
                   "mpirun -np 2 --oversubscribe");
}

std::vector<double> final_temperatures(const std::string& path, std::size_t& frames) {
  H5::H5File f(path, H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const auto T = read_doubles(f, "frames/temperature", &dims);
  frames = dims.at(0);
  return {T.end() - std::ptrdiff_t(dims.at(1)), T.end()};
}

TEST(E2eMpi, TwoProcessesHeatAsOneToTheIntegratorTolerance) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin)";
  const auto dir = scratch_dir("mpi_two");
  write_file(dir + "/bed.toml", frozen_bed_scene("off"));
  const auto one = run_tmdem("run bed.toml -o one.h5 --summary one.json", dir);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto two = run_tmdem_mpi("run bed.toml -o two.h5 --summary two.json", dir);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("heating over 2 MPI processes"), std::string::npos) << two.output;

  std::size_t frames_one = 0, frames_two = 0;
  const auto T1 = final_temperatures(dir + "/one.h5", frames_one);
  const auto T2 = final_temperatures(dir + "/two.h5", frames_two);
  ASSERT_EQ(frames_one, 11u);
  ASSERT_EQ(frames_two, frames_one);
  ASSERT_EQ(T1.size(), 360u);
  ASSERT_EQ(T2.size(), T1.size());
  double difference_K = 0.0, rise_K = 0.0;
  for (std::size_t i = 0; i < T1.size(); ++i) {
    difference_K = std::max(difference_K, std::abs(T2[i] - T1[i]));
    rise_K = std::max(rise_K, std::abs(T1[i] - 293.15));
  }
  EXPECT_GT(rise_K, 10.0);  // the bed did heat: the comparison means something
  // The two runs differ only in the preconditioner (one V-cycle over one or two processes), which
  // moves each step's Newton solution within the linear tolerance: the final temperatures agree
  // to the tolerance the integrator keeps on each step, rtol |T| + atol.
  EXPECT_LE(difference_K, kRelativeTolerance * 400.0 + kAbsoluteTolerance_K) << difference_K;
  EXPECT_DOUBLE_EQ(T2[300], 330.0);  // held

  const auto s1 = read_summary(dir + "/one.json");
  const auto s2 = read_summary(dir + "/two.json");
  EXPECT_EQ(s2["status"], "ok");
  EXPECT_EQ(s2["particles"], 360);
  EXPECT_EQ(s2["mpi"]["processes"], 2);
  EXPECT_EQ(s2["mpi"]["ghosts"], 72);  // the cut at x = 10 mm: 6 x 6 particles on each side
  EXPECT_FALSE(s1.contains("mpi"));
  // Energy: with conjugate gradients each Newton solve stops at the linear tolerance, which
  // leaves the balance at ~1e-11 in one process too (2.6e-11 here); two processes do no worse.
  EXPECT_LT(std::abs(s2["energy"]["balance_error_rel"].get<double>()), 1e-10);
  EXPECT_NEAR(s2["energy"]["boundary_heat_J"].get<double>(),
              s1["energy"]["boundary_heat_J"].get<double>(),
              kRelativeTolerance * std::abs(s1["energy"]["boundary_heat_J"].get<double>()));
  EXPECT_NEAR(s2["energy"]["final_J"].get<double>(), s1["energy"]["final_J"].get<double>(),
              kRelativeTolerance * s1["energy"]["final_J"].get<double>());
}

TEST(E2eMpi, RefusesAMovingBed) {
  if (!have_mpirun()) GTEST_SKIP() << "mpirun not installed (Debian openmpi-bin)";
  const auto dir = scratch_dir("mpi_dynamic");
  write_file(dir + "/bed.toml", frozen_bed_scene("dynamic"));
  const auto two = run_tmdem_mpi("run bed.toml -o two.h5", dir);
  EXPECT_EQ(two.exit_code, 2) << two.output;
  EXPECT_NE(two.output.find("heating over MPI (2 processes): effects.mechanics = \"dynamic\""),
            std::string::npos)
      << two.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/two.h5"));
}

}  // namespace
}  // namespace tmdem::e2e
