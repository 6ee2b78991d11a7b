#pragma once
// A heat-transfer mode adds its heat flow to each particle and its entries to the Jacobian.
// Modes are built by name (ModeRegistry) only when the scene switches them on, so a mode that is
// off is never constructed nor called. What a mode declares (switch, section, parameters,
// factory) is in thermal/modes/ModeDescription.h.
#include <span>
#include <string_view>

#include "thermal/modes/AffineHeatFlow.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

// Where a mode writes d q / d T. A nonlinear mode gives its linearisation at T (OpenFOAM-style
// split: the flow it adds is the constant part, the diagonal entry the implicit part).
// A symmetric mode (conduction) writes edge_W_per_K only; a mode whose coupling is not symmetric
// (pair radiation: d q_a / d T_b = 4 G T_b^3 but d q_b / d T_a = 4 G T_a^3) writes the two
// one-sided spans, which ThermalSystem adds on top of the symmetric part.
struct JacobianView {
  std::span<double> diagonal_W_per_K;  // d q_i / d T_i, one per node
  std::span<double> edge_W_per_K;      // d q_a / d T_b = d q_b / d T_a, one per network edge
  std::span<double> edge_ab_W_per_K{};  // d q_a / d T_b only, one per network edge
  std::span<double> edge_ba_W_per_K{};  // d q_b / d T_a only, one per network edge
};

class HeatTransferMode {
 public:
  virtual ~HeatTransferMode() = default;
  virtual std::string_view name() const = 0;

  // Adds the heat flow into each node (W) to q_W, and to boundary_W the power that enters the
  // free (not held) particles from outside them: walls, fluid, surroundings, sources, held
  // particles. Returns false when T lies outside the mode's domain (e.g. T <= 0 K for
  // radiation); the integrator then treats the evaluation as a recoverable failure.
  virtual bool add_heat_flow(const ThermalNetwork& network, std::span<const double> T_K,
                             std::span<double> q_W, double& boundary_W) const = 0;

  // Adds d q / d T at T into the view.
  virtual void add_jacobian(const ThermalNetwork& network, std::span<const double> T_K,
                            JacobianView jacobian) const = 0;

  // Called by the owning ThermalSystem whenever the edges (and their gaps) are set or replaced,
  // before any heat flow is asked for: a mode whose per-edge conductances depend only on the
  // geometry (gas in the gaps, pair view factors) computes them here once, not in every
  // right-hand side. Default: nothing to prepare.
  virtual void update_geometry(const ThermalNetwork& /*network*/) {}

  // A mode whose flow along a pair is H (T_b - T_a) with H fixed once the edges are set (contact,
  // wall and gas conduction) adds that H, before any series factor, to edge_W_per_K (one per
  // particle edge) and wall_W_per_K (one per isothermal-wall edge) and returns true. The
  // particle's own resistance is put in series with the sum over such modes
  // (thermal/modes/ParticleResistance.h); the mode then scales its H by the network's
  // edge_factor / wall_factor. Called after update_geometry. Default: no pair conductance.
  virtual bool add_pair_conductance(const ThermalNetwork& /*network*/,
                                    std::span<double> /*edge_W_per_K*/,
                                    std::span<double> /*wall_W_per_K*/) const {
    return false;
  }

  // False when add_jacobian writes the one-sided spans: the Jacobian is then not symmetric under
  // sqrt(C) scaling and the conjugate-gradient linear solver cannot be used.
  virtual bool symmetric_jacobian() const { return true; }

  // A mode whose heat flow is affine in T and fixed in time (q = K T + f) adds K and f to `out`
  // and returns true; any other mode returns false (the default), and a network with such a
  // mode has no exact reference in the accuracy study. Written from the physics, not by calling
  // add_heat_flow (AffineHeatFlow.h says why).
  virtual bool add_affine_heat_flow(const ThermalNetwork& /*network*/,
                                    AffineHeatFlow& /*out*/) const {
    return false;
  }

  // True for a mode whose boundary power is mechanical energy turned into heat (friction heat):
  // the integrators integrate that power on its own as well (ThermalIntegrator::
  // dissipation_heat_J), so the run can check it against what the mechanics dissipated.
  virtual bool heats_from_dissipation() const { return false; }
};

}  // namespace tmdem::thermal
