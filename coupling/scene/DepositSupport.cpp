#include "coupling/scene/DepositSupport.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "coupling/scene/SceneBuilder.h"

namespace tmdem::coupling {
namespace {

// The same tolerance as an overlap at start (kOverlapTolerance, of the radius): deposited
// spheres rest on the box's floor exactly up to round-off.
constexpr double kTouchingFraction = kOverlapTolerance;

struct Drop {
  double gap_m = std::numeric_limits<double>::infinity();  // along gravity; infinity: no wall
  std::optional<std::size_t> wall;
};

// How far particle p falls along `down` (unit) before it meets a plane wall facing up.
Drop drop_onto_walls(const Scene& scene, const Particle& p, const Vec3& down) {
  Drop out;
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    const Wall& wall = scene.walls[w];
    if (wall.cylinder) continue;
    // How fast the gap to the plane closes per metre of fall: n . (-down) > 0 for a floor.
    const double closing = -(wall.normal[0] * down[0] + wall.normal[1] * down[1] + wall.normal[2] * down[2]);
    if (!(closing > 0.0)) continue;
    const double gap_m = (wall_signed_distance(wall, p.position_m) - p.radius_m) / closing;
    if (gap_m < -kTouchingFraction * p.radius_m) continue;  // above it: not below the sphere
    if (gap_m < out.gap_m) {
      out.gap_m = std::max(gap_m, 0.0);
      out.wall = w;
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> unsupported_deposit_warnings(const Scene& scene,
                                                      const std::vector<DepositedBlock>& blocks) {
  std::vector<std::string> warnings;
  const Vec3& g = scene.gravity_m_per_s2;
  int axis = -1;
  for (int a = 0; a < 3; ++a)
    if (g[std::size_t(a)] != 0.0) axis = a;
  // Nothing falls without gravity (no deposit either) or without mechanics.
  if (axis < 0 || scene.effects.mechanics == MechanicsMode::Off) return warnings;
  const auto along = std::size_t(axis);
  const double down_sign = g[along] < 0.0 ? -1.0 : 1.0;
  Vec3 down{0.0, 0.0, 0.0};
  down[along] = down_sign;
  for (const DepositedBlock& block : blocks) {
    // The box's floor: its face against gravity.
    const double floor_m = down_sign < 0.0 ? block.box_min_m[along] : block.box_max_m[along];
    // Of the spheres on that floor, the one that falls farthest before a wall holds it.
    std::optional<std::size_t> worst;
    Drop worst_drop;
    for (std::size_t i = block.first; i < block.first + block.count; ++i) {
      const Particle& p = scene.particles[i];
      if (p.fixed) continue;  // held where it is laid
      const double above_floor_m = -down_sign * (p.position_m[along] - floor_m) - p.radius_m;
      if (above_floor_m > kTouchingFraction * p.radius_m) continue;  // rests on particles
      const Drop drop = drop_onto_walls(scene, p, down);
      if (drop.gap_m <= kTouchingFraction * p.radius_m) continue;  // on a wall
      if (!worst || drop.gap_m > worst_drop.gap_m) {
        worst = i;
        worst_drop = drop;
      }
    }
    if (!worst) continue;
    // Six significant digits: a gap of 1 mm, not 0.0010000000000000005 m.
    const auto figure = [](double value) {
      std::ostringstream text;
      text << value;
      return text.str();
    };
    const auto plane = [&](double coordinate_m) {
      return std::string(1, "xyz"[axis]) + " = " + figure(coordinate_m) + " m";
    };
    // Where the sphere lands along gravity: a wall across gravity is there everywhere (its
    // point's coordinate, without the round-off of floor - gap: -4e-19 m for 0).
    const auto landing_m = [&](const Drop& drop) {
      const Wall& wall = scene.walls[*drop.wall];
      bool across = true;
      for (std::size_t a = 0; a < 3; ++a) across = across && (a == along || wall.normal[a] == 0.0);
      return across ? wall.point_m[along] : floor_m + down_sign * drop.gap_m;
    };
    std::string warning = "generate[" + std::to_string(block.generate_index) +
                          "] (kind = \"deposit\") lays its spheres on the floor of its box, " +
                          plane(floor_m) + ", which is on no wall";
    if (worst_drop.wall) {
      warning += ": the bed falls " + figure(worst_drop.gap_m) + " m onto wall[" +
                 std::to_string(*worst_drop.wall) + "] at the start of the run (particle " +
                 std::to_string(*worst) + ", the longest fall) instead of starting at rest; to "
                 "lay it on that wall, set the box's floor to " + plane(landing_m(worst_drop));
    } else {
      warning += " and has no wall facing up below it (particle " + std::to_string(*worst) +
                 "): the bed falls for good; add a floor [[wall]] at " + plane(floor_m);
    }
    warnings.push_back(std::move(warning));
  }
  return warnings;
}

}  // namespace tmdem::coupling
