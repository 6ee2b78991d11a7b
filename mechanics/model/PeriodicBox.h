#pragma once
// Periodic boundaries (as in LAMMPS, LIGGGHTS, YADE): along a periodic axis space repeats
// with period L = high - low, a particle leaving at high comes back at low, and two particles
// interact through their nearest images (the minimum image convention). Positions are kept
// wrapped into [low, high) and every pair vector x_i - x_j goes through minimum_image, which
// is exact as long as no pair interacts over more than L / 2 (the detector checks it).
//
// No periodic axis (the default): minimum_image and wrap return their argument untouched, so
// a scene without [periodic] computes the same bits as before periodic boundaries existed.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

namespace tmdem::mechanics {

struct PeriodicBox {
  std::array<bool, 3> periodic{false, false, false};
  Eigen::Vector3d low = Eigen::Vector3d::Zero();   // m, only read along periodic axes
  Eigen::Vector3d high = Eigen::Vector3d::Zero();  // m, > low along periodic axes

  bool any() const { return periodic[0] || periodic[1] || periodic[2]; }
  bool along(int axis) const { return periodic[static_cast<std::size_t>(axis)]; }
  double length(int axis) const { return high[axis] - low[axis]; }  // m, the period
  // m, the shortest period (INFINITY without a periodic axis).
  double shortest_period() const {
    double period = INFINITY;
    for (int a = 0; a < 3; ++a)
      if (along(a)) period = std::min(period, length(a));
    return period;
  }
  // The length of x's part along the periodic axes (a displacement or velocity across the
  // periods; 0 without a periodic axis).
  double norm_across(const Eigen::Vector3d& x) const {
    double sq = 0.0;
    for (int a = 0; a < 3; ++a)
      if (along(a)) sq += x[a] * x[a];
    return std::sqrt(sq);
  }

  // The image of the branch vector d (m) nearest to 0: each periodic component in
  // [-L/2, L/2] (round to nearest, ties away from 0 do not matter: both images are as near).
  Eigen::Vector3d minimum_image(Eigen::Vector3d d) const {
    for (int a = 0; a < 3; ++a)
      if (along(a)) d[a] -= length(a) * std::round(d[a] / length(a));
    return d;
  }

  // x (m) moved by whole periods into [low, high) along the periodic axes.
  Eigen::Vector3d wrap(Eigen::Vector3d x) const {
    for (int a = 0; a < 3; ++a) {
      if (!along(a) || (x[a] >= low[a] && x[a] < high[a])) continue;
      const double L = length(a);
      x[a] -= L * std::floor((x[a] - low[a]) / L);
      // Rounding can land exactly on high (x just below low): that point is low's image.
      if (x[a] >= high[a]) x[a] = low[a];
      if (x[a] < low[a]) x[a] = low[a];
    }
    return x;
  }
};

}  // namespace tmdem::mechanics
