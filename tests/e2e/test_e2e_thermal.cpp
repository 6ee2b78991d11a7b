// End to end: thermal-only scenes through the tmdem program, checked against exact solutions,
// the contract's file layout and its exit codes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <nlohmann/json.hpp>

#include <cmath>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// 3 x 3 x 2 lattice of touching spheres, constant conductance, one hot corner, one held cold
// particle: small enough for a dense matrix exponential.
const std::string kThermalLattice = thermal_scene()
                                        .set("simulation.duration", 20.0)
                                        .add("generate", lattice({3, 3, 2}))
                                        .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
                                        .set(tolerances(1.0e-9))
                                        .set(output("lattice.h5", 2.0));

struct Lattice {
  Eigen::MatrixXd A;  // dT/dt = A T
  std::vector<double> T0;
};

// Built from lattice indices, independently of the program's contact search.
Lattice exact_lattice(double H, double C) {
  const int nx = 3, ny = 3, nz = 2, n = nx * ny * nz;
  auto id = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = id(i, j, k);
        const int nb[3] = {i + 1 < nx ? id(i + 1, j, k) : -1, j + 1 < ny ? id(i, j + 1, k) : -1,
                           k + 1 < nz ? id(i, j, k + 1) : -1};
        for (int b : nb) {
          if (b < 0) continue;
          K(a, b) += H; K(b, a) += H; K(a, a) -= H; K(b, b) -= H;
        }
      }
  Lattice L{K / C, std::vector<double>(n, 293.15)};
  L.T0[0] = 373.15;
  return L;
}

}  // namespace

TEST(EndToEnd, LatticeMatchesMatrixExponentialAndContractLayout) {
  const auto dir = scratch_dir("lattice");
  write_file(dir + "/lattice.toml", kThermalLattice);
  const auto r = run_tmdem("run lattice.toml --summary summary.json --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  H5::H5File f(dir + "/lattice.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(f, "format"), "tmdem-result-1");
  EXPECT_EQ(read_string_attribute(f, "status"), "ok");
  EXPECT_NE(read_string_attribute(f, "scene").find("tmdem-scene-1"), std::string::npos);

  std::vector<hsize_t> dims;
  const auto time = read_doubles(f, "/frames/time");
  const auto temp = read_doubles(f, "/frames/temperature", &dims);
  const auto C = read_doubles(f, "/particles/heat_capacity");
  ASSERT_EQ(time.size(), 11u);  // t = 0, 2, ..., 20
  ASSERT_EQ(dims.size(), 2u);
  const std::size_t n = dims[1];
  ASSERT_EQ(n, 18u);
  const double C_expected = 7800.0 * 4.0 / 3.0 * M_PI * 1e-9 * 460.0;
  EXPECT_NEAR(C[0], C_expected, 1e-12 * C_expected);

  const auto L = exact_lattice(1e-3, C_expected);
  Eigen::VectorXd T0 = Eigen::Map<const Eigen::VectorXd>(L.T0.data(), Eigen::Index(n));
  for (std::size_t fr = 0; fr < time.size(); ++fr) {
    EXPECT_NEAR(time[fr], 2.0 * double(fr), 1e-12);
    const Eigen::VectorXd exact = (L.A * time[fr]).exp() * T0;
    for (std::size_t i = 0; i < n; ++i)
      // rtol 1e-9 bounds the local error; the global error measured is 2e-6 K (6e-9 relative).
      EXPECT_NEAR(temp[fr * n + i], exact(Eigen::Index(i)), 1e-5) << "frame " << fr << " particle " << i;
  }

  // Contacts: every frame holds the 33 lattice bonds with the constant conductance.
  const auto offset = read_ints(f, "/frames/contact_offset");
  ASSERT_EQ(offset.size(), time.size() + 1);
  for (std::size_t fr = 0; fr < time.size(); ++fr) EXPECT_EQ(offset[fr + 1] - offset[fr], 33);
  const auto cond = read_doubles(f, "/contacts/conductance");
  for (double h : cond) EXPECT_EQ(h, 1e-3);

  // Every dataset carries its units.
  for (const char* name : {"/particles/radius", "/particles/mass", "/particles/heat_capacity",
                           "/particles/material", "/frames/time", "/frames/position",
                           "/frames/velocity", "/frames/temperature", "/frames/thermal_energy",
                           "/frames/boundary_heat", "/frames/contact_offset", "/contacts/pair",
                           "/contacts/normal_force", "/contacts/conductance"}) {
    H5::DataSet ds = f.openDataSet(name);
    EXPECT_TRUE(ds.attrExists("units")) << name;
  }
  const auto energy = read_doubles(f, "/frames/thermal_energy");
  for (double e : energy) EXPECT_NEAR(e, energy[0], 1e-12 * energy[0]);

  const auto summary = read_summary(dir + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["particles"], 18);
  EXPECT_EQ(summary["thermal"]["integrator"], "cvode");
  EXPECT_GT(summary["thermal"]["steps"].get<long>(), 0);
  EXPECT_LT(summary["energy"]["balance_error_rel"].get<double>(), 1e-12);
  // The contract's settle block: a packing held as given (mechanics "off") is at rest.
  EXPECT_EQ(summary["settle"]["at_rest"], true);
  EXPECT_EQ(summary["settle"]["steps"], 0);
  EXPECT_EQ(summary["settle"]["max_speed_m_s"], 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/lattice.xdmf"));
}

TEST(EndToEnd, SetOverridesAndExplicitIntegrator) {
  const auto dir = scratch_dir("set");
  write_file(dir + "/lattice.toml", kThermalLattice);
  const auto r = run_tmdem(
      "run lattice.toml -o other.h5 --quiet --set thermal.integrator=explicit "
      "--set thermal.explicit_step=0.01",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/lattice.h5"));
  H5::H5File f(dir + "/other.h5", H5F_ACC_RDONLY);
  const auto temp = read_doubles(f, "/frames/temperature");
  // First order with h = 0.01 s: close to, not equal to, the exact answer.
  const auto L = exact_lattice(1e-3, 7800.0 * 4.0 / 3.0 * M_PI * 1e-9 * 460.0);
  Eigen::VectorXd T0 = Eigen::Map<const Eigen::VectorXd>(L.T0.data(), 18);
  const Eigen::VectorXd exact = (L.A * 20.0).exp() * T0;
  double err = 0.0;
  for (int i = 0; i < 18; ++i) err = std::max(err, std::abs(temp[10 * 18 + i] - exact(i)));
  EXPECT_LT(err, 0.05);
  EXPECT_GT(err, 1e-6);
}

TEST(EndToEnd, ExplicitStepAboveBoundIsRefusedAndWritesNothing) {
  const auto dir = scratch_dir("bound");
  write_file(dir + "/lattice.toml", kThermalLattice);
  const auto r = run_tmdem("run lattice.toml --summary s.json --set thermal.integrator=explicit "
                           "--set thermal.explicit_step=100.0", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("stability bound"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/lattice.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/s.json"));
}

TEST(EndToEnd, InvalidSceneExitsTwoNamingTheKeyAndWritesNothing) {
  const auto dir = scratch_dir("invalid");
  std::string bad = kThermalLattice;
  bad.replace(bad.find("young_modulus = 2.1e11"), 22, "young_modulus = -1.0");
  write_file(dir + "/bad.toml", bad);
  auto r = run_tmdem("run bad.toml", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("material[0].young_modulus"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/lattice.h5"));
  r = run_tmdem("check bad.toml", dir);
  EXPECT_EQ(r.exit_code, 2);
  r = run_tmdem("run missing.toml", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("missing.toml"), std::string::npos) << r.output;
  r = run_tmdem("frobnicate", dir);
  EXPECT_EQ(r.exit_code, 2);
}

TEST(EndToEnd, CheckPrintsStiffness) {
  const auto dir = scratch_dir("check");
  write_file(dir + "/lattice.toml", kThermalLattice);
  const auto r = run_tmdem("check lattice.toml", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("particles: 18"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("explicit stability bound"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Biot"), std::string::npos) << r.output;
}

TEST(EndToEnd, OutputFolderMissingGivesExitFour) {
  const auto dir = scratch_dir("io");
  write_file(dir + "/lattice.toml", kThermalLattice);
  const auto r = run_tmdem("run lattice.toml -o no/such/folder/out.h5 --quiet", dir);
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("no/such/folder/out.h5"), std::string::npos) << r.output;
}
