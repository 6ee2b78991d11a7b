#pragma once
// One active contact of the last mechanics step, as handed to the coupling and the output.

#include <Eigen/Core>
#include <cstdint>

namespace tmdem::mechanics {

struct ContactForce {
  std::int64_t i = 0;                     // particle id
  std::int64_t j = 0;                     // particle id (> i), or wall_code(wall) (PairIndex.h)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, from j to i (wall: wall normal)
  double gap_m = 0.0;                     // at the start of the step; < 0 = penetration
  double normal_impulse_Ns = 0.0;         // r_n over the step, >= 0
  double normal_force_N = 0.0;            // r_n / h, the mean force over the step
  Eigen::Vector3d tangential_force_N = Eigen::Vector3d::Zero();  // r_t / h, on i
  // Mechanical power the contact's impulse dissipated over the step, -r . u_theta / h (W): the
  // mean over the step, like normal_force_N (NscdIntegrator.h, "Energy account of a step").
  // Slip work plus impact loss; negative only where a penetration is pushed out.
  double dissipated_power_W = 0.0;
};

}  // namespace tmdem::mechanics
