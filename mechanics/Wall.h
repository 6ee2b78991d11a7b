#pragma once
// An infinite plane wall. Particles live on the side the normal points to.

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

namespace tmdem::mechanics {

struct Wall {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // m, any point of the plane
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();    // unit, points into the domain
  int material = 0;                                     // index into the material list

  // Builds a wall, normalising the normal (throws if it is zero or not finite).
  static Wall through(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, int material) {
    const double length = normal.norm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      throw std::invalid_argument("wall normal must be a finite non-zero vector");
    }
    return Wall{point, normal / length, material};
  }

  // Signed distance of x from the plane, m (positive inside the domain).
  double signed_distance(const Eigen::Vector3d& x) const { return (x - point).dot(normal); }
};

}  // namespace tmdem::mechanics
