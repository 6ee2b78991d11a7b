#include "coupling/scene/SceneGenerators.h"

#include <cmath>

namespace tmdem::coupling {

Vec3 up_direction(const Vec3& gravity) {
  const double norm =
      std::sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]);
  if (norm == 0.0) return {0.0, 1.0, 0.0};
  return {-gravity[0] / norm, -gravity[1] / norm, -gravity[2] / norm};
}

std::vector<Vec3> triangular_positions(const std::vector<int>& rows, double radius,
                                       const Vec3& origin) {
  std::vector<Vec3> out;
  if (rows.empty()) return out;
  // Centre x of the bottom row; every row is centred on it.
  const double centre_x = origin[0] + (rows[0] - 1) * radius;
  double y = origin[1];
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (k > 0) {
      const int difference = std::abs(rows[k] - rows[k - 1]);
      y += difference % 2 == 1 ? std::sqrt(3.0) * radius : 2.0 * radius;
    }
    const double first_x = centre_x - (rows[k] - 1) * radius;
    for (int i = 0; i < rows[k]; ++i)
      out.push_back({first_x + 2.0 * radius * i, y, origin[2]});
  }
  return out;
}

std::vector<Vec3> column_positions(int count, double radius, const Vec3& origin, const Vec3& up) {
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double d = 2.0 * radius * i;
    out.push_back({origin[0] + d * up[0], origin[1] + d * up[1], origin[2] + d * up[2]});
  }
  return out;
}

std::vector<Vec3> lattice_positions(const std::array<int, 3>& counts, double spacing,
                                    const Vec3& origin) {
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(counts[0]) * counts[1] * counts[2]);
  for (int k = 0; k < counts[2]; ++k)
    for (int j = 0; j < counts[1]; ++j)
      for (int i = 0; i < counts[0]; ++i)
        out.push_back({origin[0] + spacing * i, origin[1] + spacing * j, origin[2] + spacing * k});
  return out;
}

}  // namespace tmdem::coupling
