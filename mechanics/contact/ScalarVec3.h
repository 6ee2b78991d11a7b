#pragma once
// A 3-vector of doubles with plain scalar arithmetic, for the Gauss-Seidel visit
// (GaussSeidelUpdate.h) and the rolling local solve (NaturalMapResidual.h). Eigen::Vector3d
// with SSE2 computes two components as a packet and the third apart, with shuffles between;
// the same visit written on this type costs 11% less on the 2,000 pour bed at rest (nlgs,
// 40 cold sweeps, 1 thread: 55.9 -> 49.7 ns of CPU per candidate per sweep; measured in
// development), at about the same instruction count (valgrind); where the time goes was not
// measured (this VM's perf has no hardware counters). Every operation rounds as Eigen's does, component by component, and a dot product
// adds left to right ((x x' + y y') + z z', as Eigen's redux of a 3-vector), so results keep
// their bits (checked on that bed: reactions and velocities after 40 sweeps, bit for bit).

#include <Eigen/Core>

namespace tmdem::mechanics {

struct ScalarVec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  ScalarVec3() = default;
  ScalarVec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit ScalarVec3(const Eigen::Vector3d& v) : x(v[0]), y(v[1]), z(v[2]) {}

  void store(Eigen::Vector3d& v) const {
    v[0] = x;
    v[1] = y;
    v[2] = z;
  }
  // Component k (0, 1, 2), as Eigen's v[k]: the kinematics (ContactKinematics.h) index both.
  double operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
  bool is_zero() const { return x == 0.0 && y == 0.0 && z == 0.0; }
  double dot(const ScalarVec3& o) const { return x * o.x + y * o.y + z * o.z; }
  double squared_norm() const { return dot(*this); }
  ScalarVec3 cross(const ScalarVec3& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
  ScalarVec3 operator+(const ScalarVec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  ScalarVec3 operator-(const ScalarVec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  ScalarVec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  friend ScalarVec3 operator*(double s, const ScalarVec3& v) { return {s * v.x, s * v.y, s * v.z}; }
};

// v += a and v -= a on a stored vector, component by component.
inline void add_to(Eigen::Vector3d& v, const ScalarVec3& a) {
  v[0] += a.x;
  v[1] += a.y;
  v[2] += a.z;
}
inline void subtract_from(Eigen::Vector3d& v, const ScalarVec3& a) {
  v[0] -= a.x;
  v[1] -= a.y;
  v[2] -= a.z;
}

}  // namespace tmdem::mechanics
