#include "mechanics/model/SequentialDeposition.h"

#include "mechanics/model/DepositionCurve.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

namespace tmdem::mechanics {
namespace {

using namespace deposition;

void check_arguments(const std::vector<double>& radii, const Vec3& box_min, const Vec3& box_max,
                     int down_axis, int down_sign, int dimension, const std::vector<Vec3>& obstacle_positions,
                     const std::vector<double>& obstacle_radii) {
  if (dimension != 2 && dimension != 3)
    throw std::invalid_argument("deposit_spheres: dimension must be 2 or 3");
  if (down_axis < 0 || down_axis >= dimension || (down_sign != 1 && down_sign != -1))
    throw std::invalid_argument(dimension == 2 ? "deposit_spheres: gravity must be along x or y in 2D"
                                               : "deposit_spheres: gravity must be along a coordinate axis");
  if (obstacle_positions.size() != obstacle_radii.size())
    throw std::invalid_argument("deposit_spheres: obstacle positions and radii differ in length");
  if (!box_min.allFinite() || !box_max.allFinite())
    throw std::invalid_argument("deposit_spheres: box corners must be finite");
  for (const double r : radii)
    if (!(r > 0.0) || !std::isfinite(r))
      throw std::invalid_argument("deposit_spheres: radii must be positive and finite");
  for (const double r : obstacle_radii)
    if (!(r > 0.0) || !std::isfinite(r))
      throw std::invalid_argument("deposit_spheres: obstacle radii must be positive and finite");
  const double r_max = radii.empty() ? 0.0 : *std::max_element(radii.begin(), radii.end());
  for (int a = 0; a < dimension; ++a) {
    if (a == down_axis) continue;
    if (box_max[a] - box_min[a] < 2.0 * r_max) {
      std::ostringstream message;
      message << "deposit_spheres: the box is narrower than the largest diameter ("
              << 2.0 * r_max << " m) along " << "xyz"[a];
      throw std::invalid_argument(message.str());
    }
  }
  if (!(box_max[down_axis] > box_min[down_axis]))
    throw std::invalid_argument("deposit_spheres: the box has no height");
}

}  // namespace


// Uniform cell grid over the box, cells one largest contact distance wide, each a list of
// sphere ids. Spheres outside the box go to the nearest cell (clamped), which is adjacent to
// every cell they can reach into.
class SequentialDeposition::Grid {
 public:
  Grid(const Vec3& lo, const Vec3& hi, double cell) : lo_(lo), cell_(cell) {
    for (int a = 0; a < 3; ++a)
      dims_[a] = static_cast<int>(std::clamp(std::ceil((hi[a] - lo[a]) / cell), 1.0, 1e7));
    const double cells = static_cast<double>(dims_[0]) * dims_[1] * dims_[2];
    if (cells > 2e7)
      throw std::invalid_argument(
          "deposit_spheres: the box is too large for the radii (over 2e7 grid cells)");
    cells_.resize(static_cast<std::size_t>(cells));
  }
  void insert(int id, const Vec3& x) { cells_[index(cell_of(x))].push_back(id); }
  // Calls f(id) for every sphere whose cell meets [lo, hi].
  template <class F>
  void for_each_in(const Vec3& lo, const Vec3& hi, F&& f) const {
    const Eigen::Vector3i a = cell_of(lo);
    const Eigen::Vector3i b = cell_of(hi);
    for (int z = a[2]; z <= b[2]; ++z)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x)
          for (const int id : cells_[index({x, y, z})]) f(id);
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& x) const {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((x[a] - lo_[a]) / cell_);
      c[a] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(dims_[a] - 1)));
    }
    return c;
  }
  std::size_t index(const Eigen::Vector3i& c) const {
    return (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  }
  Vec3 lo_;
  double cell_;
  int dims_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
};

SequentialDeposition::SequentialDeposition(const Vec3& box_min_m, const Vec3& box_max_m,
                                           int down_axis, int down_sign, double largest_radius_m,
                                           int dimension)
    : box_min_(box_min_m), box_max_(box_max_m), down_axis_(down_axis), dimension_(dimension),
      largest_(largest_radius_m) {
  check_arguments({largest_radius_m}, box_min_m, box_max_m, down_axis, down_sign, dimension, {}, {});
  up_ = Vec3::Zero();
  up_[down_axis] = -down_sign;
  floor_ = up_.dot(down_sign < 0 ? box_min_ : box_max_);
  top_ = floor_;
  grid_ = std::make_shared<Grid>(box_min_, box_max_, 2.0 * largest_);
}

namespace {
constexpr int kNoShift = 13;  // shift code of (0, 0, 0)
int shift_code(const int shift[3]) { return (shift[0] + 1) + 3 * (shift[1] + 1) + 9 * (shift[2] + 1); }
}  // namespace

void SequentialDeposition::make_periodic(int axis) {
  if (axis < 0 || axis >= dimension_ || axis == down_axis_)
    throw std::invalid_argument("SequentialDeposition: a periodic axis must lie across gravity");
  if (!centre_.empty())
    throw std::invalid_argument("SequentialDeposition: make an axis periodic before adding spheres");
  if (box_max_[axis] - box_min_[axis] < 8.0 * largest_) {
    std::ostringstream message;
    message << "SequentialDeposition: the period along " << "xyz"[axis] << " ("
            << box_max_[axis] - box_min_[axis] << " m) is shorter than 4 largest diameters ("
            << 8.0 * largest_ << " m)";
    throw std::invalid_argument(message.str());
  }
  periodic_[axis] = true;
}

void SequentialDeposition::add_sphere(const Vec3& centre_m, double radius_m) {
  if (!(radius_m > 0.0) || radius_m > largest_ || !centre_m.allFinite())
    throw std::invalid_argument("SequentialDeposition: a sphere's radius must be in (0, largest]");
  Vec3 c = centre_m;
  for (int a = 0; a < 3; ++a) {
    if (!periodic_[a]) continue;
    const double period = box_max_[a] - box_min_[a];
    c[a] -= period * std::floor((c[a] - box_min_[a]) / period);
    if (c[a] >= box_max_[a]) c[a] = box_min_[a];  // round-off of the floor above
  }
  const int owner = static_cast<int>(centre_.size());
  const auto push = [&](const Vec3& x, int code) {
    const int entry = static_cast<int>(centre_.size());
    grid_->insert(entry, x);
    centre_.push_back(x);
    radius_.push_back(radius_m);
    owner_.push_back(owner);
    shift_code_.push_back(code);
    if (code != kNoShift) entry_of_[{owner, code}] = entry;
  };
  push(c, kNoShift);
  top_ = std::max(top_, up_.dot(c) + radius_m);
  // Images across periodic sides within two largest diameters (and at corners, across both).
  const double band = 4.0 * largest_;
  int choices[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  int counts[3] = {1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    if (!periodic_[a]) continue;
    if (c[a] - box_min_[a] < band) choices[a][counts[a]++] = 1;        // image beyond max
    else if (box_max_[a] - c[a] < band) choices[a][counts[a]++] = -1;  // image below min
  }
  for (int i = 0; i < counts[0]; ++i)
    for (int j = 0; j < counts[1]; ++j)
      for (int k = 0; k < counts[2]; ++k) {
        const int shift[3] = {choices[0][i], choices[1][j], choices[2][k]};
        if (shift[0] == 0 && shift[1] == 0 && shift[2] == 0) continue;
        Vec3 x = c;
        for (int a = 0; a < 3; ++a) x[a] += shift[a] * (box_max_[a] - box_min_[a]);
        push(x, shift_code(shift));
      }
}

SequentialDeposition::Drop SequentialDeposition::drop(double r, const Vec3& start_m,
                                                      std::mt19937_64& rng,
                                                      std::size_t max_moves) {
  if (!(r > 0.0) || r > largest_)
    throw std::invalid_argument("SequentialDeposition: the radius must be in (0, largest]");
  const Vec3 up = up_;
  const Vec3 down = -up_;
  const double floor_height = floor_;
  // The faces for this radius: the floor and the four walls along gravity, offset by r. In 2D
  // the two z faces hold every centre in the plane z = mid (they carry no force: gravity lies
  // in the plane).
  Body faces[5];
  int face_count = 0;
  faces[face_count++] = {true, up, floor_height + r};
  const double mid_z = 0.5 * (box_min_[2] + box_max_[2]);
  for (int a = 0; a < 3; ++a) {
    if (a == down_axis_) continue;
    Vec3 n = Vec3::Zero();
    n[a] = 1.0;
    if (periodic_[a]) continue;
    const bool plane_of_motion = a < dimension_;
    faces[face_count++] = {true, n, plane_of_motion ? box_min_[a] + r : mid_z};
    faces[face_count++] = {true, -n, plane_of_motion ? -box_max_[a] + r : -mid_z};
  }
  const auto body = [&](int b) -> Body {
    if (b < 0) return faces[-1 - b];
    const auto k = static_cast<std::size_t>(b);
    return {false, centre_[k], r + radius_[k]};
  };

  Drop out;
  Vec3 p = start_m;
  if (dimension_ == 2) p.z() = mid_z;
  p += up * (top_ + r + largest_ - up.dot(p));  // clear of every sphere laid so far
  int supports[3];  // body ids: spheres >= 0, faces -1 - face
  int m = 0;
  const auto erase = [&](int k) {
    for (int j = k; j + 1 < m; ++j) supports[j] = supports[j + 1];
    --m;
  };
  std::size_t move = 0;
  for (; move < max_moves && !out.resting; ++move) {
    // 1. Forces of the supports: one that would have to pull lets go; so does a single one
    // holding nothing (a sphere at its equator, a wall along gravity). Three that hold: rest.
    if (m > 0) {
      Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
      for (int k = 0; k < m; ++k) N.col(k) = normal_at(body(supports[k]), p);
      const auto Nm = N.leftCols(m);
      const Eigen::VectorXd lambda = (Nm.transpose() * Nm).ldlt().solve(Nm.transpose() * up);
      int weakest = 0;
      for (int k = 1; k < m; ++k)
        if (lambda[k] < lambda[weakest]) weakest = k;
      if (lambda[weakest] < -kForceTolerance || (m == 1 && lambda[0] <= kForceTolerance)) {
        erase(weakest);
        continue;
      }
      if (m == 3) {
        out.resting = true;
        break;
      }
    }

    // 2. The curve the supports leave free, downhill from p.
    Body held[3];
    for (int k = 0; k < m; ++k) held[k] = body(supports[k]);
    const FreeMotion motion = free_motion(p, up, held, m, rng);
    if (motion.kind == FreeMotion::Rest) {
      out.resting = true;
      break;
    }
    if (motion.kind == FreeMotion::Release) {
      erase(motion.release);
      continue;
    }
    const Curve& curve = motion.curve;
    const int forces = motion.forces;
    const double* force_a = motion.force_a;
    const double* force_b = motion.force_b;
    const double* force_c = motion.force_c;

    // 3. The first event along it: a support letting go, a new contact, the lowest point.
    double s_event = curve.end;
    int event = 0;  // 0: end of the curve, 1: new contact with `touched`, 2: `dropped` lets go
    int touched = 0;
    int dropped = 0;
    for (int k = 0; k < forces; ++k) {
      const double s = first_falling_root(force_a[k], force_b[k], force_c[k], curve.end);
      if (s < s_event) {
        s_event = s;
        event = 2;
        dropped = k;
      }
    }
    const auto consider = [&](int b) {
      for (int k = 0; k < m; ++k)
        if (supports[k] == b) return;
      const double s = entry(curve, body(b));
      if (s < s_event) {
        s_event = s;
        event = 1;
        touched = b;
      }
    };
    for (int f = 0; f < face_count; ++f) consider(-1 - f);
    // Spheres the curve can reach: its bounding box grown by the largest contact distance.
    Vec3 lo, hi;
    const double reach = r + largest_;
    if (curve.line) {
      const double fall = curve.e1.dot(down);
      double length = fall > 1e-12 ? (up.dot(curve.origin) - floor_height) / fall
                                   : (box_max_ - box_min_).norm();
      if (s_event < length) length = s_event;
      const Vec3 q = curve.at(std::max(length, 0.0));
      lo = curve.origin.cwiseMin(q).array() - reach;
      hi = curve.origin.cwiseMax(q).array() + reach;
    } else {
      lo = curve.origin.array() - (curve.rho + reach);
      hi = curve.origin.array() + (curve.rho + reach);
    }
    near_.clear();
    grid_->for_each_in(lo, hi, [&](int b) { near_.push_back(b); });
    for (const int b : near_) consider(b);

    if (!std::isfinite(s_event)) {
      std::ostringstream message;
      message << "SequentialDeposition: a sphere on " << m
              << " supports found nothing to stop it along its path";
      throw std::runtime_error(message.str());
    }
    p = curve.at(s_event);
    if (event == 1) {
      supports[m++] = touched;
    } else if (event == 2) {
      erase(dropped);
    } else if (m == 1) {
      m = 0;  // off the equator: falls free
    } else {
      out.resting = true;  // the lowest point of a two-support circle
    }
    // Rolled a diameter out across a periodic side: back by one period, the supports by their
    // images on this side (all supports go if one has none: the sphere falls on from there).
    for (int a = 0; a < 3; ++a) {
      if (!periodic_[a]) continue;
      const double period = box_max_[a] - box_min_[a];
      const int back = p[a] > box_max_[a] + 2.0 * largest_ ? -1 : p[a] < box_min_[a] - 2.0 * largest_ ? 1 : 0;
      if (back == 0) continue;
      p[a] += back * period;
      bool kept = true;
      for (int k = 0; k < m && kept; ++k) {
        if (supports[k] < 0) continue;  // a face: not along a periodic axis
        const auto e = static_cast<std::size_t>(supports[k]);
        int code = shift_code_[e];
        int shift[3] = {code % 3 - 1, code / 3 % 3 - 1, code / 9 - 1};
        shift[a] += back;
        if (shift[a] < -1 || shift[a] > 1) {
          kept = false;
          break;
        }
        code = shift_code(shift);
        if (code == kNoShift) {
          supports[k] = owner_[e];
        } else if (const auto found = entry_of_.find({owner_[e], code}); found != entry_of_.end()) {
          supports[k] = found->second;
        } else {
          kept = false;
        }
      }
      if (!kept) {
        m = 0;
        out.resting = false;
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!periodic_[a]) continue;
    const double period = box_max_[a] - box_min_[a];
    p[a] -= period * std::floor((p[a] - box_min_[a]) / period);
    if (p[a] >= box_max_[a]) p[a] = box_min_[a];
  }
  out.moves = move;
  out.position = p;
  return out;
}

DepositionResult deposit_spheres(const std::vector<double>& radii, const Eigen::Vector3d& box_min,
                                 const Eigen::Vector3d& box_max, int down_axis, int down_sign,
                                 std::uint64_t seed, int dimension,
                                 const std::vector<Eigen::Vector3d>& obstacle_positions,
                                 const std::vector<double>& obstacle_radii,
                                 const std::array<bool, 3>& periodic, std::size_t max_moves) {
  check_arguments(radii, box_min, box_max, down_axis, down_sign, dimension, obstacle_positions,
                  obstacle_radii);
  DepositionResult out;
  out.positions.assign(radii.size(), Vec3::Zero());
  if (radii.empty()) return out;
  double largest = *std::max_element(radii.begin(), radii.end());
  for (const double r : obstacle_radii) largest = std::max(largest, r);
  SequentialDeposition container(box_min, box_max, down_axis, down_sign, largest, dimension);
  for (int a = 0; a < 3; ++a)
    if (periodic[a]) container.make_periodic(a);
  for (std::size_t k = 0; k < obstacle_positions.size(); ++k)
    container.add_sphere(obstacle_positions[k], obstacle_radii[k]);
  const double box_height = std::abs(box_max[down_axis] - box_min[down_axis]);

  std::mt19937_64 rng(seed);
  // Drop order: a Fisher-Yates shuffle with our own draws, so that radius classes given in
  // order (all small, then all large) are not laid in layers.
  std::vector<std::size_t> order(radii.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  for (std::size_t k = order.size() - 1; k > 0; --k) {
    const auto j = static_cast<std::size_t>(unit_draw(rng) * static_cast<double>(k + 1));
    std::swap(order[k], order[std::min(j, k)]);
  }
  for (std::size_t n = 0; n < order.size(); ++n) {
    const std::size_t id = order[n];
    const double r = radii[id];
    Vec3 start = Vec3::Zero();
    for (int a = 0; a < dimension; ++a)
      if (a != down_axis)
        start[a] = periodic[a] ? box_min[a] + unit_draw(rng) * (box_max[a] - box_min[a])
                               : box_min[a] + r + unit_draw(rng) * (box_max[a] - box_min[a] - 2.0 * r);
    const SequentialDeposition::Drop d = container.drop(r, start, rng, max_moves);
    out.moves += d.moves;
    if (!d.resting) ++out.stopped_short;
    const double height = container.height_m(d.position) + r;
    if (height > box_height * (1.0 + 1e-12)) {
      std::ostringstream message;
      message << "deposit_spheres: the box is too low: sphere " << n + 1 << " of " << radii.size()
              << " comes to rest reaching " << height << " m above the box's floor, the box is "
              << box_height << " m high";
      throw std::runtime_error(message.str());
    }
    out.positions[id] = d.position;
    container.add_sphere(d.position, r);
  }
  out.top_m = container.top_m();
  return out;
}

}  // namespace tmdem::mechanics
