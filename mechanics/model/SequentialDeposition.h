#pragma once
// Sequential deposition (Visscher & Bolsterli, Nature 239, 1972; Jodrey & Tory, Powder Technol.
// 22, 1979): a packing built by geometry instead of by a pour. Each sphere is dropped at a random
// horizontal position above the bed, falls along gravity until it touches a sphere or a face of
// the box, then rolls without friction on what it touches (keeping those contacts) down to a
// pocket where gravity is balanced by non-negative contact forces: three spheres, a sphere and a
// wall, or the floor. Only that sphere moves; the ones already laid stay put.
//
// Why: a pour spends most of its steps on the fall and the collapse of the heap; this hands the
// contact dynamics a bed in which every sphere already rests, so only its forces are left to
// settle (docs/mechanics.md "Building a bed by deposition").
//
// Each motion is a closed-form curve (a vertical line while falling, an arc over one sphere, the
// circle two supports leave free, a line along two faces), and the next event on it (a new
// contact, a support whose force would turn negative, the curve's lowest point) is the first
// root of a trigonometric or quadratic equation: no time step, exact contacts up to round-off.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <array>
#include <map>
#include <memory>
#include <random>
#include <vector>

namespace tmdem::mechanics {

// One container being filled: the spheres already laid (a cell grid of them) and the box.
class SequentialDeposition {
 public:
  // Gravity along `down_axis` (0, 1, 2) with sign `down_sign` (+1 or -1): the box's face against
  // it is the floor, the four faces along it confine the spheres, the top is open.
  // largest_radius_m: no sphere added or dropped is larger (it sizes the cells).
  // dimension 2: disks in the plane z = the middle of the box's z range (gravity along x or y);
  // only x and y must fit in the box.
  SequentialDeposition(const Eigen::Vector3d& box_min_m, const Eigen::Vector3d& box_max_m,
                       int down_axis, int down_sign, double largest_radius_m, int dimension = 3);

  // Makes `axis` (not gravity's) periodic with the box's extent along it as period, which must
  // be at least 4 largest diameters: its two faces go, a sphere near one side supports (by its
  // image) spheres across it, and positions come back wrapped into [min, max). Call before any
  // add_sphere.
  void make_periodic(int axis);

  // A sphere already in place (earlier particles of the scene, or one just dropped); on a
  // periodic axis its centre is wrapped into [min, max).
  void add_sphere(const Eigen::Vector3d& centre_m, double radius_m);

  struct Drop {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, where it came to rest
    std::size_t moves = 0;   // falls and rolls
    bool resting = false;    // false: max_moves ran out first (it touches something, no overlap)
  };
  // Drops a sphere of radius_m from above the bed at the horizontal coordinates of start_m (its
  // coordinate along gravity is ignored) and rolls it to rest; does not add it. `rng` draws the
  // direction a sphere landing exactly on top of another rolls off to.
  Drop drop(double radius_m, const Eigen::Vector3d& start_m, std::mt19937_64& rng,
            std::size_t max_moves = 1000);

  // Height of the highest sphere's top above the floor, m.
  double top_m() const { return top_ - floor_; }
  // Height of point x above the floor, m.
  double height_m(const Eigen::Vector3d& x) const { return up_.dot(x) - floor_; }

 private:
  class Grid;
  Eigen::Vector3d box_min_, box_max_;
  int down_axis_;
  int dimension_;
  Eigen::Vector3d up_;
  double floor_;     // up . p on the floor
  double largest_;   // m
  double top_;       // up . p of the highest sphere top
  bool periodic_[3] = {false, false, false};
  // Spheres and the images of those near a periodic side: centre, radius, and for an image the
  // sphere it copies and its shift code (sum over axes of 3^a (shift_a + 1), shift_a in -1..1).
  std::vector<Eigen::Vector3d> centre_;
  std::vector<double> radius_;
  std::vector<int> owner_;
  std::vector<int> shift_code_;
  std::map<std::pair<int, int>, int> entry_of_;  // (owner, shift code) -> entry, images only
  std::shared_ptr<Grid> grid_;
  std::vector<int> near_;  // reused candidate list
};

struct DepositionResult {
  std::vector<Eigen::Vector3d> positions;  // m, one per radius, in the order of the radii given
  std::size_t moves = 0;                   // falls and rolls, all spheres together
  std::size_t stopped_short = 0;  // spheres left where max_moves ran out (kept, no overlap)
  double top_m = 0.0;             // height of the highest sphere's top above the floor
};

// Drops the spheres of `radii` (m) into the box [box_min, box_max] (m) in an order shuffled with
// `seed`, each from a uniformly drawn horizontal position, on top of the spheres of
// `obstacle_positions` / `obstacle_radii` (m) that are there already (dimension and periodic
// axes as for SequentialDeposition; drops on a periodic axis are drawn over its whole period). Reproducible on every
// machine (std::mt19937_64, own mapping to [0, 1)).
// Throws std::invalid_argument for bad arguments and std::runtime_error when a sphere comes to
// rest reaching above the box's top (the box is too low for the count).
DepositionResult deposit_spheres(const std::vector<double>& radii, const Eigen::Vector3d& box_min,
                                 const Eigen::Vector3d& box_max, int down_axis, int down_sign,
                                 std::uint64_t seed, int dimension = 3,
                                 const std::vector<Eigen::Vector3d>& obstacle_positions = {},
                                 const std::vector<double>& obstacle_radii = {},
                                 const std::array<bool, 3>& periodic = {false, false, false},
                                 std::size_t max_moves = 1000);

}  // namespace tmdem::mechanics
