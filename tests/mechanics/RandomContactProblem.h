#pragma once
// A random contact problem for the bitwise tests of the Gauss-Seidel visit and sweep: every
// branch of the visit (open, stick, slip; rolling at and below its limit; walls and a piston).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics::test {

// Draws of our own (std::uniform_real_distribution's are implementation-defined).
struct Draws {
  std::mt19937_64 engine;
  explicit Draws(std::uint64_t seed) : engine(seed) {}
  double uniform(double a, double b) {
    return a + (b - a) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
  }
  Eigen::Vector3d vector(double size, int dimension) {
    return Eigen::Vector3d(uniform(-size, size), uniform(-size, size), dimension == 3 ? uniform(-size, size) : 0.0);
  }
};

// 40 spheres (mass ~1e-4 kg, radius ~1 mm), a fixed floor and a piston (wall bodies 40 and 41),
// 160 contacts between random pairs or a sphere and a wall, each with a random unit normal and
// its tangents, Delassus blocks from the bodies (w_n = 1/m_i + 1/m_j, w_t adds R^2/I for each
// sphere, w_r = 1/I_i + 1/I_j), a random position term and warm start: open, sticking and
// slipping contacts, at and below the rolling limit.
inline ContactProblem random_contact_problem(int dimension, std::uint64_t seed) {
  Draws d(seed);
  ContactProblem p;
  p.dimension = dimension;
  p.rolling = true;
  const int spheres = 40, contacts = 160;
  std::vector<double> radius(spheres);
  for (int b = 0; b < spheres; ++b) {
    radius[b] = d.uniform(0.5e-3, 1e-3);
    const double mass = d.uniform(0.5e-4, 2e-4), inertia = 0.4 * mass * radius[b] * radius[b];
    p.inverse_mass.push_back(1.0 / mass);
    p.inverse_inertia.push_back(1.0 / inertia);
    p.free_velocity.push_back(d.vector(0.05, dimension));
    Eigen::Vector3d spin = d.vector(50.0, 3);
    if (dimension == 2) spin = Eigen::Vector3d(0.0, 0.0, spin.z());
    p.free_angular_velocity.push_back(spin);
  }
  p.add_fixed_wall_bodies(2);
  p.inverse_mass[spheres + 1] = 1.0 / 1e-3;  // the piston
  p.free_velocity[spheres + 1] = Eigen::Vector3d(0.0, -0.01, 0.0);
  p.resize_contacts(contacts);
  for (int c = 0; c < contacts; ++c) {
    const int i = static_cast<int>(d.engine() % spheres);
    int j = static_cast<int>(d.engine() % (spheres + 2));
    if (j == i) j = (i + 1) % spheres;
    const bool wall = j >= spheres;
    Eigen::Vector3d n = d.vector(1.0, dimension);
    if (wall) n = Eigen::Vector3d(0.0, 1.0, 0.0);  // the walls' normal, along which the piston moves
    n.normalize();
    const Eigen::Vector3d t1 = dimension == 2 ? Eigen::Vector3d(-n.y(), n.x(), 0.0) : n.unitOrthogonal();
    const double im_j = p.inverse_mass[j];  // 0 for the floor
    const double ii_i = p.inverse_inertia[i], ii_j = wall ? 0.0 : p.inverse_inertia[j];
    const double lever_j = wall ? 0.0 : radius[j];
    p.body_i[c] = i;
    p.body_j[c] = wall ? wall_code<std::int32_t>(static_cast<std::size_t>(j - spheres)) : j;
    p.normal[c] = n;
    p.tangent1[c] = t1;
    p.tangent2[c] = n.cross(t1);
    p.lever_i[c] = radius[i];
    p.lever_j[c] = lever_j;
    p.w_n[c] = p.inverse_mass[i] + im_j;
    p.w_t[c] = p.w_n[c] + radius[i] * radius[i] * ii_i + lever_j * lever_j * ii_j;
    p.bias[c] = d.uniform(-0.02, 0.02);
    p.mu[c] = d.uniform(0.1, 0.6);
    p.rolling_radius[c] = wall ? radius[i] : radius[i] * radius[j] / (radius[i] + radius[j]);
    p.rolling_limit[c] = d.uniform(0.0, 0.1) * p.rolling_radius[c];
    p.w_r[c] = ii_i + ii_j;
  }
  return p;
}

}  // namespace tmdem::mechanics::test
