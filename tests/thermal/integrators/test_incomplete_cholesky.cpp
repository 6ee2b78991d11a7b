// The pcg preconditioner: IC(0) is exact where Cholesky creates no fill, and elsewhere matches
// the matrix on its pattern (the defining property of a zero-fill incomplete factor).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "thermal/ThermalTestSupport.h"
#include "thermal/integrators/IncompleteCholesky.h"

using namespace tmdem::thermal;
using namespace tmdem::thermal::testing;

namespace {

// A = I - gamma J, in pattern order.
std::vector<double> newton_values(const ThermalSystem& sys, double gamma) {
  auto v = scaled_jacobian(sys);
  for (auto& x : v) x *= -gamma;
  for (std::size_t i = 0; i < sys.size(); ++i) v[std::size_t(sys.pattern().diagonal_slot[i])] += 1.0;
  return v;
}

Eigen::MatrixXd dense(const JacobianPattern& p, const std::vector<double>& v) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(Eigen::Index(p.size()), Eigen::Index(p.size()));
  for (std::size_t j = 0; j < p.size(); ++j)
    for (auto k = p.column_start[j]; k < p.column_start[j + 1]; ++k)
      A(p.row_index[std::size_t(k)], Eigen::Index(j)) = v[std::size_t(k)];
  return A;
}

}  // namespace

TEST(IncompleteCholesky, ExactOnAChainWhereCholeskyHasNoFill) {
  ThermalNetwork net = chain_network(30, 1e-3, 1e-4);
  for (int i = 0; i < 30; ++i) net.heat_capacity_J_per_K[i] = 1e-3 * (1.0 + 0.1 * i);
  auto sys = make_system(net, {"contact_conduction"});
  // Factored the way the integrators do it: -gamma * J plus a unit diagonal shift.
  IncompleteCholesky ic;
  ic.analyse(sys->pattern());
  ASSERT_TRUE(ic.factor(scaled_jacobian(*sys), -50.0, std::vector<double>(sys->size(), 1.0)));
  const Eigen::MatrixXd A = dense(sys->pattern(), newton_values(*sys, 50.0));
  std::mt19937_64 rng(5);
  Eigen::VectorXd b(30);
  for (int i = 0; i < 30; ++i) b(i) = double(rng() % 1000) / 100.0 - 5.0;
  std::vector<double> r(b.data(), b.data() + 30), z(30);
  ic.solve(r, z);
  const Eigen::VectorXd x = A.llt().solve(b);
  for (int i = 0; i < 30; ++i) EXPECT_NEAR(z[std::size_t(i)], x(i), 1e-12 * std::max(1.0, std::abs(x(i))));
}

TEST(IncompleteCholesky, MatchesTheMatrixOnItsPatternWithFill) {
  // A ring with chords: Cholesky would fill in; IC(0) reproduces A on A's pattern.
  ThermalNetwork net;
  const int n = 40;
  net.resize_nodes(n);
  for (int i = 0; i < n; ++i) net.heat_capacity_J_per_K[i] = 1e-3 * (1.0 + (i % 7));
  for (int i = 0; i < n; ++i) net.add_edge(i, (i + 1) % n, 1e-4 * (1 + i % 3));
  for (int i = 0; i < n; i += 5) net.add_edge(i, (i + 17) % n, 3e-4);
  auto sys = make_system(net, {"contact_conduction"});
  const auto v = newton_values(*sys, 20.0);
  IncompleteCholesky ic;
  ic.analyse(sys->pattern());
  ASSERT_TRUE(ic.factor(v, 1.0, std::vector<double>(sys->size(), 0.0)));
  const auto& p = sys->pattern();
  const Eigen::MatrixXd A = dense(p, v);
  // Rebuild M = L L^T column by column from solves: M^-1 e_j = z_j, so M = (Z)^-1.
  Eigen::MatrixXd Z(n, n);
  for (int j = 0; j < n; ++j) {
    std::vector<double> e(n, 0.0), z(n);
    e[std::size_t(j)] = 1.0;
    ic.solve(e, z);
    for (int i = 0; i < n; ++i) Z(i, j) = z[std::size_t(i)];
  }
  const Eigen::MatrixXd M = Z.inverse();
  for (std::size_t j = 0; j < p.size(); ++j)
    for (auto k = p.column_start[j]; k < p.column_start[j + 1]; ++k) {
      const auto i = p.row_index[std::size_t(k)];
      EXPECT_NEAR(M(i, Eigen::Index(j)), A(i, Eigen::Index(j)), 1e-10) << i << "," << j;
    }
  EXPECT_GT((M - A).norm(), 1e-8) << "no fill was dropped: the test would not tell IC(0) from LU";
}
