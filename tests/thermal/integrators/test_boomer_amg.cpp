// The "amg" linear solver: hypre BoomerAMG as a preconditioner of the symmetric Newton matrix
// (BoomerAmgPreconditioner.h) and of the steady state. Judged against dense Cholesky solves and
// KLU, and on what multigrid is for: CG iterations that do not grow with the lattice.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>
#include <random>

#include "thermal/ThermalTestSupport.h"
#include "thermal/integrators/BoomerAmgPreconditioner.h"
#include "thermal/integrators/IncompleteCholesky.h"
#include "thermal/integrators/ThermalSolverError.h"
#include "thermal/steady/SteadyStateSolver.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// An L^3 simple-cubic network with conductances log-uniform over `spread` decades below 1e-2
// W/K (4: a stiff bed, strong chains beside weak contacts; 0: all equal), capacities over one
// decade; the x = 0 face touches a wall at 400 K, the x = L-1 face one at 300 K.
ThermalNetwork stiff_lattice(int L, double spread = 4.0, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> decades(-2.0 - spread, -2.0), capacity(1e-3, 1e-2);
  ThermalNetwork net;
  net.resize_nodes(std::size_t(L) * L * L);
  for (auto& C : net.heat_capacity_J_per_K) C = capacity(rng);
  auto id = [L](int x, int y, int z) { return std::int32_t((z * L + y) * L + x); };
  for (int z = 0; z < L; ++z)
    for (int y = 0; y < L; ++y)
      for (int x = 0; x < L; ++x) {
        if (x + 1 < L) net.add_edge(id(x, y, z), id(x + 1, y, z), std::pow(10.0, decades(rng)));
        if (y + 1 < L) net.add_edge(id(x, y, z), id(x, y + 1, z), std::pow(10.0, decades(rng)));
        if (z + 1 < L) net.add_edge(id(x, y, z), id(x, y, z + 1), std::pow(10.0, decades(rng)));
      }
  for (int z = 0; z < L; ++z)
    for (int y = 0; y < L; ++y) {
      net.add_wall_edge(id(0, y, z), 400.0, 1e-3);
      net.add_wall_edge(id(L - 1, y, z), 300.0, 1e-3);
    }
  net.isothermal_walls = 2;
  return net;
}

std::unique_ptr<ThermalSystem> conduction(const ThermalNetwork& net) {
  return make_system(net, {"contact_conduction", "wall_conduction"});
}

// sqrt(C): the integrators' state scale (BoomerAmgPreconditioner::set_state_scale).
std::vector<double> state_scale(const ThermalSystem& sys) {
  std::vector<double> s(sys.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = std::sqrt(sys.network().heat_capacity_J_per_K[i]);
  return s;
}

Eigen::MatrixXd dense(const JacobianPattern& p, const std::vector<double>& v, double scale,
                      double shift) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(Eigen::Index(p.size()), Eigen::Index(p.size()));
  for (std::size_t j = 0; j < p.size(); ++j)
    for (auto k = p.column_start[j]; k < p.column_start[j + 1]; ++k)
      A(p.row_index[std::size_t(k)], Eigen::Index(j)) = scale * v[std::size_t(k)];
  A.diagonal().array() += shift;
  return A;
}

Eigen::VectorXd random_vector(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::VectorXd b(Eigen::Index(n), 1);
  for (auto& x : b) x = g(rng);
  return b;
}

}  // namespace

// CG with the V-cycle solves the stiff Newton matrix (gamma 1e4 s: nearly the Laplacian, whose
// conductances span four decades) to the dense Cholesky answer.
TEST(BoomerAmg, ConjugateGradientsMatchCholeskyOnAStiffNewtonMatrix) {
  const auto sys = conduction(stiff_lattice(6));
  const auto& p = sys->pattern();
  const auto J = scaled_jacobian(*sys);
  const double gamma = 1e4;
  const std::vector<double> shift(sys->size(), 1.0);
  BoomerAmgPreconditioner amg;
  amg.analyse(p);
  ASSERT_TRUE(amg.factor(J, -gamma, shift));
  const Eigen::VectorXd b = random_vector(sys->size(), 3);
  std::vector<double> x(sys->size(), 0.0);
  const auto result = amg.solve_cg({b.data(), sys->size()}, x, 1e-12, 200);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.relative_residual, 1e-12);
  const Eigen::MatrixXd A = dense(p, J, -gamma, 1.0);
  const Eigen::VectorXd exact = A.llt().solve(b);
  const Eigen::Map<const Eigen::VectorXd> got(x.data(), Eigen::Index(x.size()));
  // The residual bound times the condition number (~1e4 here) bounds the error.
  EXPECT_LT((got - exact).norm(), 1e-7 * exact.norm());
  EXPECT_LT((A * got - b).norm(), 1e-11 * b.norm());
}

// One V-cycle is a contraction in the energy norm of M (what makes it a CG preconditioner),
// and a far better one than IC(0) on a stiff matrix.
TEST(BoomerAmg, OneVCycleContractsTheErrorMoreThanIncompleteCholesky) {
  const auto sys = conduction(stiff_lattice(8));
  const auto& p = sys->pattern();
  const auto J = scaled_jacobian(*sys);
  const std::vector<double> shift(sys->size(), 1.0);
  const Eigen::MatrixXd A = dense(p, J, -1e4, 1.0);
  const Eigen::VectorXd x = random_vector(sys->size(), 5);
  const Eigen::VectorXd r = A * x;
  auto energy_error = [&](NewtonPreconditioner& pre) {
    pre.analyse(p);
    EXPECT_TRUE(pre.factor(J, -1e4, shift));
    std::vector<double> z(sys->size());
    pre.solve({r.data(), sys->size()}, z);
    const Eigen::VectorXd e = x - Eigen::Map<const Eigen::VectorXd>(z.data(), Eigen::Index(z.size()));
    return std::sqrt(e.dot(A * e) / x.dot(A * x));
  };
  BoomerAmgPreconditioner amg;
  amg.set_state_scale(state_scale(*sys));
  IncompleteCholesky ic;
  const double amg_error = energy_error(amg), ic_error = energy_error(ic);
  EXPECT_LT(amg_error, 0.6);
  EXPECT_LT(amg_error, 0.8 * ic_error) << "IC(0) " << ic_error;
}

// Preconditioned CG written out (so both preconditioners are judged by the same loop): the
// iterations to ||b - A x|| <= tolerance ||b|| from x = 0.
int pcg_iterations(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                   NewtonPreconditioner& pre, double tolerance, int max_iterations) {
  const std::size_t n = std::size_t(b.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), r = b, z(b.size());
  pre.solve({r.data(), n}, {z.data(), n});
  Eigen::VectorXd d = z;
  double rz = r.dot(z);
  for (int k = 1; k <= max_iterations; ++k) {
    const Eigen::VectorXd Ad = A * d;
    const double alpha = rz / d.dot(Ad);
    x += alpha * d;
    r -= alpha * Ad;
    if (r.norm() <= tolerance * b.norm()) return k;
    pre.solve({r.data(), n}, {z.data(), n});
    const double rz_next = r.dot(z);
    d = z + (rz_next / rz) * d;
    rz = rz_next;
  }
  return max_iterations + 1;
}

Eigen::SparseMatrix<double> sparse(const JacobianPattern& p, const std::vector<double>& v,
                                   double scale, double shift) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t j = 0; j < p.size(); ++j)
    for (auto k = p.column_start[j]; k < p.column_start[j + 1]; ++k)
      entries.emplace_back(Eigen::Index(p.row_index[std::size_t(k)]), Eigen::Index(j),
                           scale * v[std::size_t(k)] + (p.row_index[std::size_t(k)] == std::int64_t(j) ? shift : 0.0));
  Eigen::SparseMatrix<double> A(Eigen::Index(p.size()), Eigen::Index(p.size()));
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// The point of multigrid: CG iterations that do not grow with the lattice where IC(0)'s grow
// with its width (M in the integrators' scaled state, the V-cycle with its state scale).
// Measured, 8^3 -> 32^3 nodes, to 1e-8: equal conductances amg 11 -> 12, IC(0) 24 -> 82; four
// random decades (each contact drawn alone, a harder graph than a bed's chains) amg 14 -> 19,
// IC(0) 34 -> 137. Without the state scale the V-cycle went 15 -> 31 on equal conductances.
TEST(BoomerAmg, IterationsGrowFarLessThanIncompleteCholeskyWithTheLattice) {
  for (double spread : {0.0, 4.0}) {
    std::map<int, std::pair<int, int>> iterations;  // L -> (amg, ic)
    for (int L : {8, 32}) {
      const auto sys = conduction(stiff_lattice(L, spread));
      const auto J = scaled_jacobian(*sys);
      const std::vector<double> shift(sys->size(), 1.0);
      const auto A = sparse(sys->pattern(), J, -1e4, 1.0);
      const Eigen::VectorXd b = random_vector(sys->size(), 11);
      BoomerAmgPreconditioner amg;
      amg.set_state_scale(state_scale(*sys));
      IncompleteCholesky ic;
      for (NewtonPreconditioner* pre : std::initializer_list<NewtonPreconditioner*>{&amg, &ic}) {
        pre->analyse(sys->pattern());
        ASSERT_TRUE(pre->factor(J, -1e4, shift));
      }
      iterations[L] = {pcg_iterations(A, b, amg, 1e-8, 2000), pcg_iterations(A, b, ic, 1e-8, 2000)};
    }
    const auto [amg8, ic8] = iterations[8];
    const auto [amg32, ic32] = iterations[32];
    const std::string figures = std::to_string(spread) + " decades: amg " + std::to_string(amg8) +
                                " -> " + std::to_string(amg32) + ", IC(0) " + std::to_string(ic8) +
                                " -> " + std::to_string(ic32);
    EXPECT_LE(amg32, spread == 0.0 ? amg8 * 13 / 10 + 1 : amg8 * 16 / 10) << figures;
    EXPECT_LT(amg32, 0.3 * ic32) << figures;
  }
}

// The steady state by multigrid CG is KLU's to the Newton tolerance.
TEST(BoomerAmg, SteadyStateEqualsKlu) {
  const auto sys = conduction(stiff_lattice(10));
  const std::vector<double> T0(sys->size(), 300.0);
  const auto klu = solve_steady_state(*sys, T0);
  SteadyStateOptions options;
  options.linear_solver = LinearSolverKind::Amg;
  const auto amg = solve_steady_state(*sys, T0, options);
  EXPECT_EQ(amg.factorizations, 1);  // linear: one hierarchy serves both Newton steps
  EXPECT_GT(amg.cg_iterations, 0);
  double largest = 0.0;
  for (std::size_t i = 0; i < T0.size(); ++i) largest = std::max(largest, std::abs(amg.T_K[i] - klu.T_K[i]));
  EXPECT_LT(largest, 1e-9) << "K";
  EXPECT_LT(amg.max_residual_W, 1e-12);
}

// A one-sided Jacobian (pair radiation) cannot go to conjugate gradients: refused, naming the
// solver, not solved wrongly.
TEST(BoomerAmg, SteadyStateRefusesAOneSidedJacobian) {
  ThermalNetwork net = chain_network(3, 0.01, 1e-3);
  net.surface_area_m2.assign(3, 1e-5);
  net.emissivity.assign(3, 0.8);
  net.radius_m.assign(3, 1e-3);
  net.held[0] = 1;
  const auto sys = make_system(net, {"contact_conduction", "particle_radiation"});
  if (sys->symmetric_jacobian()) GTEST_SKIP() << "particle_radiation became symmetric";
  SteadyStateOptions options;
  options.linear_solver = LinearSolverKind::Amg;
  try {
    solve_steady_state(*sys, std::vector<double>{400.0, 300.0, 300.0}, options);
    FAIL() << "amg accepted a one-sided Jacobian";
  } catch (const ThermalSolverError& e) {
    EXPECT_NE(std::string(e.what()).find("amg"), std::string::npos) << e.what();
  }
}
