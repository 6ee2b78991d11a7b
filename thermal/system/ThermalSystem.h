#pragma once
// The thermal ODE C_i dT_i/dt = q_i(T): a network plus the heat-transfer modes a scene switched
// on. Integrators see only this class: the right-hand side, the Jacobian (as a CSC matrix or as
// a matrix-free product), and the stability bound of the explicit update.
//
// Held particles keep their temperature: their rows are zero (dT/dt = 0) and, in the Jacobian,
// so are their columns. The solution is unchanged by the latter (a held unknown never receives
// a Newton correction) and it keeps the Jacobian symmetric under sqrt(C) scaling, which the
// conjugate-gradient solver needs.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "thermal/modes/HeatTransferMode.h"
#include "thermal/system/JacobianEvaluation.h"
#include "thermal/system/JacobianPattern.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

class ThermalSystem {
 public:
  ThermalSystem(ThermalNetwork network, std::vector<std::unique_ptr<HeatTransferMode>> modes);

  const ThermalNetwork& network() const { return network_; }
  std::size_t size() const { return network_.node_count(); }
  const std::vector<std::unique_ptr<HeatTransferMode>>& modes() const { return modes_; }

  // Takes the edges (particle-particle and particle-wall) and the contacts' dissipated powers of
  // `edges`; node data is untouched.
  // Same pairs in the same order: a values-only change. Otherwise the contact graph changed
  // shape and the pattern is rebuilt.
  void replace_edges(const ThermalNetwork& edges);
  std::uint64_t topology_version() const { return topology_version_; }

  // The time the heat flow is evaluated at: walls whose temperature follows a table take their
  // value at t_s (nothing else depends on time). Integrators set it before each evaluation.
  void set_time(double t_s);
  double time_s() const { return time_s_; }
  std::uint64_t values_version() const { return values_version_; }

  // Heat flow into every node, W (held nodes included), and the boundary power into the free
  // particles, W. False: T is outside some mode's domain (recoverable).
  bool heat_flow(std::span<const double> T_K, std::span<double> q_W, double& boundary_W) const;
  // The part of the boundary power that the modes turning mechanical dissipation into heat
  // (HeatTransferMode::heats_from_dissipation) put into the free particles, W. It does not
  // depend on T: constant over a mechanical step.
  double dissipation_boundary_W() const;
  // dT/dt = q / C, zero for held nodes.
  bool time_derivative(std::span<const double> T_K, std::span<double> dTdt_K_per_s,
                       double& boundary_W) const;

  // Built when first asked for after each change of the contact graph's shape: a system whose
  // Jacobian is never assembled (the whole bed's, in each process of a run over MPI, where each
  // integrates its own piece) never holds it (152 MB at 10^6 particles).
  const JacobianPattern& pattern() const;
  // Evaluates d q / d T of every mode at T into J (resized to the current network; no
  // allocation once J has seen the largest edge count).
  void evaluate_jacobian(std::span<const double> T_K, JacobianEvaluation& J) const;
  // Values of J = d(dT/dt)/dT in pattern order, scaled as S J S^-1 with S = diag(scale)
  // (empty scale: none), from an evaluation of the current contact graph. With
  // temperature-dependent capacities J is C(T)^-1 dq/dT, without the capacity's own slope:
  // with S = C(T) that is the exact Jacobian d q / d E of the enthalpy state.

  void jacobian_values(const JacobianEvaluation& J, std::span<double> values,
                       std::span<const double> scale = {}) const;
  // Jv = S J S^-1 v, matrix-free, from an evaluation of the current contact graph.
  void jacobian_times(const JacobianEvaluation& J, std::span<const double> v, std::span<double> Jv,
                      std::span<const double> scale = {}) const;

  // Largest stable forward-Euler step, s: 2 / lambda_max with lambda_max bounded by Gershgorin
  // row sums of J evaluated at T = T_max everywhere (T_max bounds the run's temperatures: the
  // nonlinear radiation term is largest there). Infinity when nothing couples or exchanges heat.
  // Uses its own evaluation: a caller's JacobianEvaluation is never touched.
  double explicit_stability_bound_s(double T_max_K) const;

  // sum_i int_0^T_i C_i(T) dT: sum C_i T_i for constant capacities.
  double thermal_energy_J(std::span<const double> T_K) const;

  // False when some mode's Jacobian is not symmetric (HeatTransferMode::symmetric_jacobian).
  bool symmetric_jacobian() const;

 private:
  mutable std::vector<double> dissipation_scratch_W_;  // dissipation_boundary_W's node flows
  // The particle's own resistance: the network's series factors from the modes' pair
  // conductances (thermal/modes/ParticleResistance.h), after every update_geometry.
  void update_series_factors();
  // Throws std::logic_error when J was evaluated before the contact graph changed shape.
  void check_evaluation(const JacobianEvaluation& J) const;
  // C_i at J's temperatures (the network's constant C_i when nothing depends on T).
  double capacity(const JacobianEvaluation& J, std::size_t i) const;

  ThermalNetwork network_;
  std::vector<std::unique_ptr<HeatTransferMode>> modes_;
  mutable JacobianPattern pattern_;
  mutable bool pattern_built_ = false;
  std::uint64_t topology_version_ = 0;
  std::uint64_t values_version_ = 0;
  double time_s_ = 0.0;
};

}  // namespace tmdem::thermal
