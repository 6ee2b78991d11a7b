// [periodic]: the periods are read with [simulation] (an [[import]]'s contacts measure their
// normals through them), checked against the particles and walls once those are read.
#include <algorithm>

#include "coupling/scene/SceneBuilder.h"
#include "mechanics/integrator/NscdParameters.h"

namespace tmdem::coupling {

namespace {
constexpr const char* kAxisNames[3] = {"x", "y", "z"};
}  // namespace

void SceneBuilder::read_periodic() {
  const auto table = root_.optional_table("periodic", true);
  if (!table) return;
  const SceneTable& t = *table;
  PeriodicSettings& periodic = scene_.periodic;
  for (int a = 0; a < 3; ++a) {
    const char* key = kAxisNames[a];
    if (!t.has(key)) continue;
    if (a == 2 && scene_.dimension == 2)
      t.fail(key, "a 2D scene (simulation.dimension = 2) cannot be periodic along z");
    const std::vector<double> range = t.required_numbers(key);
    if (range.size() != 2)
      t.fail(key, "expected [min, max], 2 numbers (got " + std::to_string(range.size()) + ")");
    if (!(range[1] > range[0]))
      t.fail(key, "max must be > min (got [" + format_number(range[0]) + ", " +
                      format_number(range[1]) + "])");
    periodic.axis[std::size_t(a)] = true;
    periodic.low_m[std::size_t(a)] = range[0];
    periodic.high_m[std::size_t(a)] = range[1];
  }
}

void SceneBuilder::check_periodic_bodies() {
  const PeriodicSettings& periodic = scene_.periodic;
  if (!periodic.any()) return;
  const SceneTable t = section("periodic", true);
  double largest_radius_m = 0.0;
  for (const auto& p : scene_.particles) largest_radius_m = std::max(largest_radius_m, p.radius_m);
  // The detector needs twice the contact reach, 2 r_max + its smallest margin, in each period
  // (mechanics/detection/ContactDetector.h): one image of a pair within reach, never two.
  const double shortest_m =
      2.0 * (2.0 * largest_radius_m + mechanics::NscdParameters{}.min_margin_fraction * largest_radius_m);
  for (int a = 0; a < 3; ++a) {
    if (!periodic.axis[std::size_t(a)]) continue;
    if (periodic.length_m(a) < shortest_m)
      t.fail(kAxisNames[a], "the period " + format_number(periodic.length_m(a)) +
                                " m is shorter than 2 x (largest diameter + 0.1 x largest radius) "
                                "= " + format_number(shortest_m) + " m");
    for (std::size_t w = 0; w < scene_.walls.size(); ++w) {
      const Wall& wall = scene_.walls[w];
      if (wall.cylinder || wall.normal[std::size_t(a)] != 0.0)
        t.fail(kAxisNames[a], "wall[" + std::to_string(w) + "] crosses the periodic axis " +
                                  kAxisNames[a] + " (walls must be planes whose normal has no " +
                                  kAxisNames[a] + " component)");
    }
  }
  // Wrapped by whole periods: the same packing, every centre in [min, max).
  const mechanics::PeriodicBox box = periodic_box(periodic);
  for (auto& p : scene_.particles) {
    const Eigen::Vector3d x = box.wrap(Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]));
    p.position_m = {x[0], x[1], x[2]};
  }
}

}  // namespace tmdem::coupling
