#include "mechanics/model/DepositionCurve.h"

#include <algorithm>

namespace tmdem::mechanics::deposition {

// First s in [0, hi] where h(s) = A cos s + B sin s - C goes from positive to zero (h' <= 0),
// or infinity. h(s) = R cos(s - phi) - C, so its falling root is phi + acos(C / R). A falling
// root at the very start (|s| within the tolerance, h'(0) = B < 0) is an event at 0: the sphere
// already touches and is moving in.
double first_falling_root(double A, double B, double C, double hi) {
  const double R = std::hypot(A, B);
  if (!(R > 0.0) || std::abs(C) >= R) return kInf;
  double s = std::remainder(std::atan2(B, A) + std::acos(C / R), kTwoPi);
  if (std::abs(s) <= kStartTolerance) {
    if (B < 0.0) return 0.0;
    s = kTwoPi;
  } else if (s < 0.0) {
    s += kTwoPi;
  }
  return s <= hi ? s : kInf;
}

// Where a curve first enters body b (the body's contact condition turning from clear to
// touching), or infinity.
double entry(const Curve& c, const Body& b) {
  if (c.line) {
    if (b.plane) {
      const double rate = b.vector.dot(c.e1);
      if (!(rate < 0.0)) return kInf;
      const double s = (b.offset - b.vector.dot(c.origin)) / rate;
      return std::max(s, 0.0);  // already through it (round-off): touching now
    }
    const Vec3 w = c.origin - b.vector;
    const double half_b = w.dot(c.e1);
    const double cc = w.squaredNorm() - b.offset * b.offset;
    const double disc = half_b * half_b - cc;
    // No contact, or a grazing one (the line tangent to the sphere: it does not move in).
    if (!(disc > kStartTolerance * b.offset * b.offset) ||
        cc < -kStartTolerance * b.offset * b.offset)
      return kInf;
    const double s = -half_b - std::sqrt(disc);
    if (s >= 0.0) return s;
    // Touching at the start within round-off and moving in: an event at 0.
    return (half_b < 0.0 && cc <= kStartTolerance * b.offset * b.offset) ? 0.0 : kInf;
  }
  if (b.plane) {
    return first_falling_root(c.rho * b.vector.dot(c.e1), c.rho * b.vector.dot(c.e2),
                              b.offset - b.vector.dot(c.origin), c.end);
  }
  const Vec3 w = c.origin - b.vector;
  return first_falling_root(2.0 * c.rho * w.dot(c.e1), 2.0 * c.rho * w.dot(c.e2),
                            b.offset * b.offset - w.squaredNorm() - c.rho * c.rho, c.end);
}

FreeMotion free_motion(const Vec3& p, const Vec3& up, const Body* supports, int m,
                       std::mt19937_64& rng) {
  const Vec3 down = -up;
  FreeMotion out;
  Curve& curve = out.curve;
  double* force_a = out.force_a;
  double* force_b = out.force_b;
  double* force_c = out.force_c;
  if (m == 0) {
    curve.origin = p;
    curve.e1 = down;
  } else if (m == 1) {
    const Body& b = supports[0];
    if (b.plane) {  // slide down the face; on the floor: at rest
      const Vec3 along = down - down.dot(b.vector) * b.vector;
      if (along.norm() < 1e-12) {
        out.kind = FreeMotion::Rest;
        return out;
      }
      curve.origin = p;
      curve.e1 = along.normalized();
    } else {  // roll over the sphere in the vertical plane, down to its equator
      curve.line = false;
      curve.origin = b.vector;
      curve.rho = b.offset;
      curve.e1 = (p - b.vector).normalized();
      Vec3 t = down - down.dot(curve.e1) * curve.e1;
      if (t.norm() < 1e-9) t = random_horizontal(up, rng);  // landed right on top
      curve.e2 = t.normalized();
      // Its force, up . n(s), is zero at the equator: there it falls free.
      curve.end = first_falling_root(up.dot(curve.e1), up.dot(curve.e2), 0.0, kTwoPi);
      if (!std::isfinite(curve.end)) curve.end = 0.0;
    }
  } else {
    const Body& b1 = supports[0];
    const Body& b2 = supports[1];
    if (b1.plane && b2.plane) {  // along the edge of two faces
      Vec3 along = b1.vector.cross(b2.vector);
      if (along.norm() < 1e-12) {  // parallel faces: keep one
        out.kind = FreeMotion::Release;
        out.release = 1;
        return out;
      }
      along.normalize();
      if (up.dot(along) > 0.0) along = -along;
      if (std::abs(up.dot(along)) < 1e-12) {
        out.kind = FreeMotion::Rest;
        return out;
      }
      curve.origin = p;
      curve.e1 = along;
    } else {
      // The circle of centres touching both: axis a, centre `origin`, radius rho.
      curve.line = false;
      Vec3 a;
      if (b1.plane || b2.plane) {
        const Body& face = b1.plane ? b1 : b2;
        const Body& ball = b1.plane ? b2 : b1;
        a = face.vector;
        const double height = face.offset - a.dot(ball.vector);  // m, along a from the centre
        curve.origin = ball.vector + height * a;
        curve.rho = std::sqrt(std::max(0.0, ball.offset * ball.offset - height * height));
      } else {
        const Vec3 d = b2.vector - b1.vector;
        const double L = d.norm();
        a = d / L;
        const double along = (b1.offset * b1.offset - b2.offset * b2.offset + L * L) / (2.0 * L);
        curve.origin = b1.vector + along * a;
        curve.rho = std::sqrt(std::max(0.0, b1.offset * b1.offset - along * along));
      }
      if (!(curve.rho > 1e-12 * std::max(b1.offset, b2.offset))) {  // touching at one point
        out.kind = FreeMotion::Release;
        out.release = 1;
        return out;
      }
      const Vec3 radial = p - curve.origin;
      curve.e1 = (radial - radial.dot(a) * a).normalized();
      Vec3 t = a.cross(curve.e1);
      if (up.dot(t) > 0.0) t = -t;
      if (std::abs(up.dot(t)) < 1e-12 && up.dot(curve.e1) < 0.0) {  // at its lowest point
        out.kind = FreeMotion::Rest;
        return out;
      }
      curve.e2 = t;
      curve.end = std::atan2(-up.dot(curve.e2), -up.dot(curve.e1));
      if (curve.end <= 0.0) curve.end += kTwoPi;
      // Support forces along the circle: n_k = beta_k a + gamma_k r(s), so with
      // u_a = up . a and u_r(s) = up . r(s), lambda_1 det = gamma_2 u_a - beta_2 u_r(s) and
      // lambda_2 det = beta_1 u_r(s) - gamma_1 u_a: each zero where A cos s + B sin s = C.
      double beta[2], gamma[2];
      const Body* bs[2] = {&b1, &b2};
      for (int k = 0; k < 2; ++k) {
        if (bs[k]->plane) {
          beta[k] = bs[k]->vector.dot(a);
          gamma[k] = 0.0;
        } else {
          beta[k] = (curve.origin - bs[k]->vector).dot(a) / bs[k]->offset;
          gamma[k] = curve.rho / bs[k]->offset;
        }
      }
      const double sign = beta[0] * gamma[1] - beta[1] * gamma[0] < 0.0 ? -1.0 : 1.0;
      const double ua = up.dot(a);
      const double ue1 = up.dot(curve.e1);
      const double ue2 = up.dot(curve.e2);
      force_a[0] = -sign * beta[1] * ue1;
      force_b[0] = -sign * beta[1] * ue2;
      force_c[0] = -sign * gamma[1] * ua;
      force_a[1] = sign * beta[0] * ue1;
      force_b[1] = sign * beta[0] * ue2;
      force_c[1] = sign * gamma[0] * ua;
      out.forces = 2;
    }
  }
  return out;
}

}  // namespace tmdem::mechanics::deposition
