// KLU's predicted cost of one factorisation (thermal/integrators/KluFactorisationCost.h) against
// the closed-form elimination counts of two patterns AMD cannot reorder into less work: a chain
// (tridiagonal: no fill) and a complete graph (dense: every entry fills). Counts of Gaussian
// elimination on an n x n matrix with the diagonal pivots: L and U each hold n diagonal entries
// plus the off-diagonal ones below (above) it; the flops are one division per off-diagonal entry
// of L and a multiply and a subtract per update of the trailing matrix.
#include <gtest/gtest.h>

#include <cmath>

#include "thermal/integrators/KluFactorisationCost.h"
#include "thermal/network/ThermalNetwork.h"
#include "thermal/system/JacobianPattern.h"

namespace tmdem::thermal {
namespace {

JacobianPattern pattern_of(const ThermalNetwork& net) {
  JacobianPattern p;
  p.build(net);
  return p;
}

ThermalNetwork chain(int n) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  for (int i = 0; i + 1 < n; ++i) net.add_edge(i, i + 1, 1.0);
  return net;
}

ThermalNetwork complete_graph(int n) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) net.add_edge(i, j, 1.0);
  return net;
}

TEST(KluFactorisationCost, ChainHasNoFill) {
  const int n = 50;
  const auto cost = analyse_klu_factorisation(pattern_of(chain(n)));
  // L: n diagonal + (n - 1) below; U the same. Column k: one division, one update (2 flops).
  EXPECT_DOUBLE_EQ(cost.factor_nonzeros, 2.0 * (2.0 * n - 1.0));
  EXPECT_DOUBLE_EQ(cost.flops, 3.0 * (n - 1.0));
  EXPECT_TRUE(std::isnan(cost.factorisation_s));  // analysed, not timed
}

TEST(KluFactorisationCost, CompleteGraphFillsEverything) {
  const int n = 12;
  const auto cost = analyse_klu_factorisation(pattern_of(complete_graph(n)));
  const double below = n * (n - 1) / 2.0;                     // strictly lower entries
  const double updates = (n - 1.0) * n * (2.0 * n - 1.0) / 6.0;  // sum over k of (n - 1 - k)^2
  EXPECT_DOUBLE_EQ(cost.factor_nonzeros, 2.0 * (n + below));
  EXPECT_DOUBLE_EQ(cost.flops, below + 2.0 * updates);
}

TEST(KluFactorisationCost, TimingKeepsTheAnalysisAndMeasuresBoth) {
  const auto pattern = pattern_of(complete_graph(30));
  const auto analysed = analyse_klu_factorisation(pattern);
  const auto timed = time_klu_factorisation(pattern);
  EXPECT_EQ(timed.flops, analysed.flops);
  EXPECT_EQ(timed.factor_nonzeros, analysed.factor_nonzeros);
  EXPECT_TRUE(std::isfinite(timed.factorisation_s) && timed.factorisation_s >= 0.0);
  EXPECT_TRUE(std::isfinite(timed.solve_s) && timed.solve_s >= 0.0);
}

}  // namespace
}  // namespace tmdem::thermal
