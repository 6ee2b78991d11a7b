#pragma once
// A wall: an infinite plane (particles on the side the normal points to), or an infinite
// cylinder with the particles inside it. Contacts ask only signed_distance and normal_at, so
// the detector, the touching-pair search and NSCD treat both shapes alike.
//
// A plane wall with a mass is a piston: a body with one translational degree of freedom along
// its normal, pushed into the domain by load_N and gravity (NscdIntegrator.h). Its point and
// velocity then change from step to step; every other wall is fixed.

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

namespace tmdem::mechanics {

enum class WallShape { Plane, Cylinder };

struct Wall {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // m, any point of the plane / of the axis
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();    // unit; plane: points into the domain;
                                                        // cylinder: the axis direction
  int material = 0;                                     // index into the material list
  WallShape shape = WallShape::Plane;
  double radius_m = 0.0;                                // cylinder radius
  double mass_kg = 0.0;            // piston mass; 0: a fixed wall
  double load_N = 0.0;             // piston: imposed force along the normal (into the domain)
  double velocity_m_per_s = 0.0;   // piston: velocity along the normal

  bool moves() const { return mass_kg > 0.0; }

  // Makes this plane a piston of `mass_kg` pushed into the domain by `load_N` (throws for a
  // cylinder, a mass that is not positive and finite or a load that is not finite).
  Wall& make_piston(double piston_mass_kg, double piston_load_N) {
    if (shape != WallShape::Plane) throw std::invalid_argument("a piston must be a plane wall");
    if (!(piston_mass_kg > 0.0) || !std::isfinite(piston_mass_kg))
      throw std::invalid_argument("piston mass must be positive and finite");
    if (!std::isfinite(piston_load_N)) throw std::invalid_argument("piston load must be finite");
    mass_kg = piston_mass_kg;
    load_N = piston_load_N;
    return *this;
  }

  // Builds a wall, normalising the normal (throws if it is zero or not finite).
  static Wall through(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, int material) {
    const double length = normal.norm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      throw std::invalid_argument("wall normal must be a finite non-zero vector");
    }
    return Wall{point, normal / length, material};
  }

  // A cylinder around the axis through `axis_point` along `axis`, particles inside.
  static Wall cylinder(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
                       double radius_m, int material) {
    Wall w = through(axis_point, axis, material);
    if (!(radius_m > 0.0) || !std::isfinite(radius_m))
      throw std::invalid_argument("cylinder wall radius must be positive and finite");
    w.shape = WallShape::Cylinder;
    w.radius_m = radius_m;
    return w;
  }

  // Signed distance of x from the wall surface, m (positive inside the domain).
  double signed_distance(const Eigen::Vector3d& x) const {
    if (shape == WallShape::Plane) return (x - point).dot(normal);
    return radius_m - radial(x).norm();
  }

  // Unit normal of the surface at the point nearest to x, pointing into the domain (towards x
  // for a particle inside). A point on the axis has every radial direction: any one will do.
  Eigen::Vector3d normal_at(const Eigen::Vector3d& x) const {
    if (shape == WallShape::Plane) return normal;
    const Eigen::Vector3d r = radial(x);
    const double length = r.norm();
    if (length > 0.0) return -r / length;
    const Eigen::Vector3d any = std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return -(any - any.dot(normal) * normal).normalized();
  }

 private:
  // The part of x - point across the axis.
  Eigen::Vector3d radial(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - point;
    return d - d.dot(normal) * normal;
  }
};

}  // namespace tmdem::mechanics
