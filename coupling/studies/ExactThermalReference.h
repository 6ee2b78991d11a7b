#pragma once
// The exact solution of a linear thermal network, for the accuracy study (contract section 5).
//
// With only linear modes (contact and wall conduction, convection, sources) the thermal ODE is
// affine, dT/dt = A T + b, and T(t) = exp(t M) [T0; 1] with M = [[A, b], [0, 0]] (dense matrix
// exponential, Eigen MatrixFunctions: Pade 13 with scaling and squaring, applied to the
// symmetrised system in y = sqrt(C) T). A and b are assembled
// here from the network arrays and the mode settings alone, independently of ThermalSystem's
// own right-hand side and Jacobian, so that the study measures the integrators against an
// answer they did not help compute. Held particles have zero rows (dT/dt = 0).
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

// A and b for the network with the named modes switched on (registry names, see
// thermal/modes/ModeList.h). Empty when a mode is not linear ("radiation") or not known here: such a
// network has no exact reference. The one place in coupling/ that names modes, on purpose: an
// independent re-derivation of their physics is what makes it a reference; parameters come
// from the modes' own declarations (defaults included).
std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalNetwork& network,
                                                         const std::vector<std::string>& mode_names,
                                                         const thermal::ModeSettings& settings);
// The same for a system's network and the modes it holds.
std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalSystem& system,
                                                         const thermal::ModeSettings& settings);

// T(t_s) from T(0) = T0_K. Throws std::runtime_error if the result is not finite.
std::vector<double> exact_affine_temperatures(const AffineThermalSystem& system,
                                              std::span<const double> T0_K, double t_s);

}  // namespace tmdem::coupling
