#pragma once
// The exact solution of a linear thermal network, for the accuracy study (contract section 5).
//
// With only linear modes (contact and wall conduction, convection, sources) the thermal ODE is
// affine, dT/dt = A T + b, and T(t) = exp(t M) [T0; 1] with M = [[A, b], [0, 0]] (dense matrix
// exponential, Eigen MatrixFunctions: Pade 13 with scaling and squaring, applied to the
// symmetrised system in y = sqrt(C) T). A and b are assembled from what each mode states of its
// affine part, written apart from its right-hand side and Jacobian, so that the study measures
// the integrators against an answer they did not help compute. Held particles have zero rows (dT/dt = 0).
#include <Eigen/Dense>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "thermal/modes/ModeSettings.h"
#include "thermal/network/ThermalNetwork.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

struct AffineThermalSystem {
  Eigen::MatrixXd A;      // 1/s
  Eigen::VectorXd b;      // K/s
  // sqrt(C_i): the exponential is taken of S A S^-1 (S = diag(scale)), which is symmetric on the
  // free particles, instead of the far from normal A of a bed whose heat capacities differ by
  // orders of magnitude; scaling and squaring loses much less there. Empty: no scaling.
  Eigen::VectorXd scale;
};

// A and b for the network with the named modes switched on (registry names, thermal/modes/
// ModeList.h; an unknown name throws std::invalid_argument listing the valid ones), built with
// `settings`. Each mode states its own affine part (HeatTransferMode::add_affine_heat_flow), so
// nothing here names a mode. Empty when a mode is not affine ("radiation"), or the network's
// properties follow T or its wall temperatures follow a table: such a network has no exact
// reference; *why_not (when given) then says why, naming the modes.
std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalNetwork& network,
                                                         const std::vector<std::string>& mode_names,
                                                         const thermal::ModeSettings& settings,
                                                         std::string* why_not = nullptr);
// The same for a system's network and the modes it holds.
std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalSystem& system,
                                                         std::string* why_not = nullptr);

// T(t_s) from T(0) = T0_K. Throws std::runtime_error if the result is not finite.
std::vector<double> exact_affine_temperatures(const AffineThermalSystem& system,
                                              std::span<const double> T0_K, double t_s);

}  // namespace tmdem::coupling
