#pragma once
// The geometry of a sphere moving in a sequential deposition (SequentialDeposition.h): what it
// can touch, the closed-form curves it follows (a line while falling or sliding, a circle while
// rolling on one or two supports), where a curve first meets a body or lets a support go, and
// which curve the supports leave free. Internal to the deposition; every function is exact up
// to round-off, with the allowances below.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>

namespace tmdem::mechanics::deposition {

using Vec3 = Eigen::Vector3d;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Relative round-off allowances: a root this close to the start of a curve is the start itself;
// a support force this close to 0 (in units of the sphere's weight) is taken as 0.
inline constexpr double kStartTolerance = 1e-10;
inline constexpr double kForceTolerance = 1e-12;

// Uniform double in [0, 1) from the top 53 bits of one draw: identical on every machine
// (std::uniform_real_distribution's output is implementation-defined).
inline double unit_draw(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// What a moving sphere of radius r can touch: another sphere (its centre at contact distance
// `offset` = r + r_j from `vector`) or a face of the box (inward normal `vector`, touched when
// vector . p = offset).
struct Body {
  bool plane = false;
  Vec3 vector = Vec3::Zero();
  double offset = 0.0;
};

// A motion: a line p(s) = origin + s e1 (s in m), or a circle p(s) = origin + rho (cos s e1 +
// sin s e2) (s in rad) with s from 0; `end` is the parameter of its lowest point (infinity for a
// line). The centre moves along it from s = 0, downhill.
struct Curve {
  bool line = true;
  Vec3 origin = Vec3::Zero();
  Vec3 e1 = Vec3::Zero();
  Vec3 e2 = Vec3::Zero();
  double rho = 0.0;
  double end = kInf;
  Vec3 at(double s) const {
    return line ? Vec3(origin + s * e1) : Vec3(origin + rho * (std::cos(s) * e1 + std::sin(s) * e2));
  }
};

// First s in [0, hi] where h(s) = A cos s + B sin s - C goes from positive to zero (h' <= 0),
// or infinity. h(s) = R cos(s - phi) - C, so its falling root is phi + acos(C / R). A falling
// root at the very start (|s| within the tolerance, h'(0) = B < 0) is an event at 0: the sphere
// already touches and is moving in.
double first_falling_root(double A, double B, double C, double hi);

// Where a curve first enters body b (the body's contact condition turning from clear to
// touching), or infinity.
double entry(const Curve& c, const Body& b);

// Outward contact normal of body b at centre position p (the direction its force pushes).
inline Vec3 normal_at(const Body& b, const Vec3& p) {
  return b.plane ? b.vector : Vec3((p - b.vector).normalized());
}

// A horizontal unit vector (perpendicular to `up`), drawn: the direction a sphere landing exactly
// on top of another rolls off to.
inline Vec3 random_horizontal(const Vec3& up, std::mt19937_64& rng) {
  const double angle = kTwoPi * unit_draw(rng);
  const Vec3 a = up.unitOrthogonal();
  const Vec3 b = up.cross(a);
  return std::cos(angle) * a + std::sin(angle) * b;
}

// What the supports (m of them, at most 2; the sphere's centre at p) leave the sphere: a curve
// to follow downhill from p, with the support forces that can reach zero along it (force k is
// zero where force_a[k] cos s + force_b[k] sin s = force_c[k]); a support to let go (two faces
// in parallel, two spheres touching it at one point); or rest (on the floor, at the lowest
// point of its circle). `rng` draws the way off for a sphere landed exactly on top of another.
struct FreeMotion {
  enum Kind { Follow, Release, Rest };
  Kind kind = Follow;
  int release = 0;  // for Release: the index of the support that lets go
  Curve curve;
  int forces = 0;   // support forces that can reach zero along the curve (0 or 2)
  double force_a[2] = {0.0, 0.0}, force_b[2] = {0.0, 0.0}, force_c[2] = {0.0, 0.0};
};
FreeMotion free_motion(const Vec3& p, const Vec3& up, const Body* supports, int m,
                       std::mt19937_64& rng);

}  // namespace tmdem::mechanics::deposition
