#pragma once
// Random sequential placement of non-overlapping spheres in a box, for
// [[generate]] kind = "random". Reproducible on every machine: std::mt19937_64 is fully
// specified by the standard, and the mapping to [0, 1) is our own (the output of
// std::uniform_real_distribution is implementation-defined).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace tmdem::coupling {

struct RandomPlacement {
  std::vector<Eigen::Vector3d> positions;  // m
  std::vector<double> radii;               // m
};

// Places `count` spheres fully inside [box_min, box_max] without overlaps.
// Radii: particle k gets radii[c] where c is the first class whose cumulative fraction
// (fractions normalised by their sum) exceeds (k + 0.5) / count, so ids 0.. take the first
// class, then the second, and so on, with class sizes as close to the fractions as integer
// counts allow. Placement goes from the largest radius down (easier to fit), each sphere
// drawing uniform positions until it overlaps nobody.
// dimension 2: centres are in the plane z = (box_min.z + box_max.z) / 2 and only x, y must
// fit in the box. Throws std::invalid_argument for bad arguments and std::runtime_error
// when a sphere cannot be placed after max_attempts_per_particle draws.
RandomPlacement place_random(std::size_t count, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, const std::vector<double>& radii,
                             const std::vector<double>& fractions, std::uint64_t seed,
                             int dimension, std::size_t max_attempts_per_particle = 100000);

// The same, also keeping clear of the spheres already in `avoid` (e.g. those of earlier
// generators), so that several generators can fill one box. Spheres of `avoid` that never
// touch a candidate change nothing: disjoint boxes give exactly the placement above.
RandomPlacement place_random(std::size_t count, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, const std::vector<double>& radii,
                             const std::vector<double>& fractions, std::uint64_t seed,
                             int dimension, const RandomPlacement& avoid,
                             std::size_t max_attempts_per_particle = 100000);

// The radius of each of `count` ids by class (as place_random gives them): id k gets radii[c],
// c the first class whose cumulative fraction (normalised by their sum) exceeds (k + 0.5) /
// count. Assumes radii and fractions already checked (same length, radii > 0, fractions >= 0
// with a positive sum).
std::vector<double> class_radii(std::size_t count, const std::vector<double>& radii,
                                const std::vector<double>& fractions);

// Uniform double in [0, 1) from the top 53 bits of one 64-bit draw; identical everywhere.
double uniform_unit(std::uint64_t bits);

}  // namespace tmdem::coupling
