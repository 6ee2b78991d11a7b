#pragma once
// The exact solution of a linear thermal network, for the accuracy study (contract section 5).
//
// With only linear modes (contact and wall conduction, convection, sources) the thermal ODE is
// affine, C dT/dt = K T + f. K and f are assembled from what each mode states of its affine
// part, written apart from its right-hand side and Jacobian, so that the study measures the
// integrators against an answer they did not help compute. Held particles have no rows
// (dT/dt = 0).
//
// Two solvers of the same system:
// - coupling/studies/SparseExactReference.h: the study's reference, any size, with an error
//   bound in kelvin (Chebyshev series of the exponential on the sparse matrix);
// - exact_affine_temperatures below: the dense matrix exponential (Eigen MatrixFunctions, Pade 13
//   with scaling and squaring) of M = [[A, b], [0, 0]] on the system symmetrised in
//   y = sqrt(C) T. O(n^3) time and O(n^2) memory (2,000 particles: 21 s, 313 MB) and no error
//   bound: kept as the independent check of the sparse solver on small networks (tests, bench).
#include <Eigen/SparseCore>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "thermal/modes/ModeSettings.h"
#include "thermal/network/ThermalNetwork.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::coupling {

struct AffineThermalSystem {
  // K = d q / d T, W/K: the rows of the free particles (held particles: empty rows), each entry
  // the sum of what the modes wrote for it, summed in long double.
  Eigen::SparseMatrix<long double, Eigen::RowMajor> K_W_per_K;
  // Per row, a bound of sum_j |K_ij stored - K_ij exact| from that summing (an entry written n
  // times: gamma_(n-1) times the sum of its |terms|): the sparse reference's error bound uses it.
  std::vector<long double> K_rounding_W_per_K;
  std::vector<double> f_W;              // q at T = 0, W (0 for held particles)
  std::vector<double> C_J_per_K;        // heat capacities
  std::vector<std::uint8_t> held;       // 1: temperature held
  std::size_t size() const { return C_J_per_K.size(); }
};

// K and f for the network with the named modes switched on (registry names, thermal/modes/
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

// T(t_s) from T(0) = T0_K by the dense matrix exponential (see above). Throws
// std::runtime_error if the result is not finite.
std::vector<double> exact_affine_temperatures(const AffineThermalSystem& system,
                                              std::span<const double> T0_K, double t_s);

}  // namespace tmdem::coupling
