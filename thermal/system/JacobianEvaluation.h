#pragma once
// d q / d T of every heat-transfer mode at one temperature field, W/K: one value per node (the
// diagonal) and one per edge (the symmetric off-diagonal pair). ThermalSystem::evaluate_jacobian
// fills it and jacobian_values / jacobian_times read it. The caller owns it, so two users of one
// system (an integrator between its setup and its solves, and a stability or diagnostic check)
// can never overwrite each other's Jacobian.
#include <vector>

namespace tmdem::thermal {

struct JacobianEvaluation {
  std::vector<double> diagonal_W_per_K;  // per node
  std::vector<double> edge_W_per_K;      // per edge, in the network's edge order (symmetric)
  std::vector<double> edge_ab_W_per_K;   // per edge: extra d q_a / d T_b (non-symmetric modes)
  std::vector<double> edge_ba_W_per_K;   // per edge: extra d q_b / d T_a
  // Temperature-dependent capacities only (empty otherwise): C_i(T_i), J/K.
  std::vector<double> capacity_J_per_K;
};

}  // namespace tmdem::thermal
