#include "coupling/scene/RandomPlacement.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace tmdem::coupling {

double uniform_unit(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

std::vector<double> class_radii(std::size_t count, const std::vector<double>& radii,
                                const std::vector<double>& fractions) {
  const double fraction_sum = std::accumulate(fractions.begin(), fractions.end(), 0.0);
  std::vector<double> cumulative(radii.size());
  double running = 0.0;
  for (std::size_t c = 0; c < radii.size(); ++c) {
    running += fractions[c] / fraction_sum;
    cumulative[c] = running;
  }
  cumulative.back() = 1.0;  // guard against round-off leaving the last class unreachable
  std::vector<double> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double position_in_order = (static_cast<double>(k) + 0.5) / static_cast<double>(count);
    std::size_t c = 0;
    while (c + 1 < radii.size() && !(position_in_order < cumulative[c])) ++c;
    out[k] = radii[c];
  }
  return out;
}

RandomPlacement place_random(std::size_t count, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, const std::vector<double>& radii,
                             const std::vector<double>& fractions, std::uint64_t seed,
                             int dimension, std::size_t max_attempts_per_particle) {
  return place_random(count, box_min, box_max, radii, fractions, seed, dimension,
                      RandomPlacement{}, max_attempts_per_particle);
}

RandomPlacement place_random(std::size_t count, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, const std::vector<double>& radii,
                             const std::vector<double>& fractions, std::uint64_t seed,
                             int dimension, const RandomPlacement& avoid,
                             std::size_t max_attempts_per_particle) {
  if (avoid.positions.size() != avoid.radii.size()) {
    throw std::invalid_argument("place_random: avoid has positions and radii of different lengths");
  }
  if (dimension != 2 && dimension != 3) {
    throw std::invalid_argument("place_random: dimension must be 2 or 3");
  }
  if (radii.empty()) throw std::invalid_argument("place_random: no radius given");
  if (fractions.size() != radii.size()) {
    throw std::invalid_argument("place_random: radii and fractions differ in length");
  }
  double fraction_sum = 0.0;
  for (std::size_t c = 0; c < radii.size(); ++c) {
    if (!(radii[c] > 0.0) || !std::isfinite(radii[c])) {
      throw std::invalid_argument("place_random: radii must be positive and finite");
    }
    if (!(fractions[c] >= 0.0) || !std::isfinite(fractions[c])) {
      throw std::invalid_argument("place_random: fractions must be non-negative and finite");
    }
    fraction_sum += fractions[c];
  }
  if (!(fraction_sum > 0.0)) throw std::invalid_argument("place_random: fractions sum to 0");
  if (!box_min.allFinite() || !box_max.allFinite()) {
    throw std::invalid_argument("place_random: box corners must be finite");
  }
  const int axes = dimension;  // axes that must contain the sphere: x, y (and z in 3D)

  RandomPlacement out;
  out.radii = class_radii(count, radii, fractions);
  out.positions.resize(count, Eigen::Vector3d::Zero());
  if (count == 0) return out;
  const double r_max = *std::max_element(out.radii.begin(), out.radii.end());
  for (int a = 0; a < axes; ++a) {
    if (box_max[a] - box_min[a] < 2.0 * r_max) {
      std::ostringstream message;
      message << "place_random: the box is narrower than a particle diameter ("
              << 2.0 * r_max << " m) along axis " << "xyz"[a];
      throw std::invalid_argument(message.str());
    }
  }

  // Grid over the box with cells of one largest reach (one largest diameter without `avoid`):
  // a new sphere can only overlap spheres in its own or the adjacent cells. Each cell holds a
  // linked list of sphere ids; ids from `count` on are the spheres of `avoid`.
  const double avoid_r_max =
      avoid.radii.empty() ? 0.0 : *std::max_element(avoid.radii.begin(), avoid.radii.end());
  const double cell = r_max + std::max(r_max, avoid_r_max);
  int dims[3] = {1, 1, 1};
  double cells = 1.0;
  for (int a = 0; a < axes; ++a) {
    // Counted in double first: a box 1e43 cells wide does not fit an int (the fuzzer found it).
    const double along = std::max(1.0, std::floor((box_max[a] - box_min[a]) / cell));
    cells *= along;
    if (cells > 1e8) throw std::invalid_argument("place_random: box too large for the radius");
    dims[a] = static_cast<int>(along);
  }
  std::vector<std::int64_t> head(static_cast<std::size_t>(cells), -1);
  std::vector<std::int64_t> next(count + avoid.positions.size(), -1);
  auto cell_coordinate = [&](const Eigen::Vector3d& x, int a) {
    const double extent = box_max[a] - box_min[a];
    const int c = static_cast<int>((x[a] - box_min[a]) / extent * dims[a]);
    return std::clamp(c, 0, dims[a] - 1);
  };

  auto cell_of = [&](const Eigen::Vector3d& x) {
    const int cz = axes == 3 ? cell_coordinate(x, 2) : 0;
    return (static_cast<std::size_t>(cz) * dims[1] + cell_coordinate(x, 1)) * dims[0] +
           cell_coordinate(x, 0);
  };
  // Spheres of `avoid` that cannot reach into the box are left out; the others go to the cell
  // of their centre clamped to the box, which is adjacent to every cell they can reach.
  for (std::size_t k = 0; k < avoid.positions.size(); ++k) {
    const Eigen::Vector3d& x = avoid.positions[k];
    bool near = true;
    for (int a = 0; a < axes; ++a) {
      near = near && x[a] > box_min[a] - avoid.radii[k] && x[a] < box_max[a] + avoid.radii[k];
    }
    if (!near) continue;
    const auto id = static_cast<std::int64_t>(count + k);
    const auto cell_id = cell_of(x);
    next[id] = head[cell_id];
    head[cell_id] = id;
  }
  auto position_of = [&](std::int64_t id) -> const Eigen::Vector3d& {
    const auto u = static_cast<std::size_t>(id);
    return u < count ? out.positions[u] : avoid.positions[u - count];
  };
  auto radius_of = [&](std::int64_t id) {
    const auto u = static_cast<std::size_t>(id);
    return u < count ? out.radii[u] : avoid.radii[u - count];
  };

  // Largest radius first; ties in id order.
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return out.radii[a] > out.radii[b]; });

  std::mt19937_64 rng(seed);
  const double plane_z = 0.5 * (box_min.z() + box_max.z());
  for (std::size_t placed = 0; placed < count; ++placed) {
    const std::size_t id = order[placed];
    const double r = out.radii[id];
    bool ok = false;
    Eigen::Vector3d x;
    for (std::size_t attempt = 0; attempt < max_attempts_per_particle && !ok; ++attempt) {
      x = Eigen::Vector3d(0.0, 0.0, plane_z);
      for (int a = 0; a < axes; ++a) {
        x[a] = box_min[a] + r + uniform_unit(rng()) * (box_max[a] - box_min[a] - 2.0 * r);
      }
      int c[3] = {0, 0, 0};
      for (int a = 0; a < axes; ++a) c[a] = cell_coordinate(x, a);
      ok = true;
      for (int dz = (axes == 3 ? -1 : 0); dz <= (axes == 3 ? 1 : 0) && ok; ++dz) {
        for (int dy = -1; dy <= 1 && ok; ++dy) {
          for (int dx = -1; dx <= 1 && ok; ++dx) {
            const int cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
            if (cx < 0 || cx >= dims[0] || cy < 0 || cy >= dims[1] || cz < 0 || cz >= dims[2]) {
              continue;
            }
            const auto cell_id = (static_cast<std::size_t>(cz) * dims[1] + cy) * dims[0] + cx;
            for (std::int64_t other = head[cell_id]; other >= 0; other = next[other]) {
              const double reach = r + radius_of(other);
              if ((position_of(other) - x).squaredNorm() < reach * reach) {
                ok = false;
                break;
              }
            }
          }
        }
      }
    }
    if (!ok) {
      std::ostringstream message;
      message << "random placement: could not place particle " << placed + 1 << " of "
              << count << " (radius " << r << " m) after " << max_attempts_per_particle
              << " attempts; the box is too small for this many particles";
      throw std::runtime_error(message.str());
    }
    out.positions[id] = x;
    const auto cell_id = cell_of(x);
    next[id] = head[cell_id];
    head[cell_id] = static_cast<std::int64_t>(id);
  }
  return out;
}

}  // namespace tmdem::coupling
