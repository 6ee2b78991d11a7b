#include "mechanics/solvers/SpatialContactOrder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {
namespace {

// The bits of x spread to every third bit (x < 2^21).
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

void SpatialContactOrder::update(const ContactProblem& problem,
                                 const std::vector<Eigen::Vector3d>& position_m, double cell_m) {
  const std::size_t n = problem.particle_count;
  if (position_m.size() != n) {
    throw std::invalid_argument("SpatialContactOrder: " + std::to_string(position_m.size()) +
                                " positions for " + std::to_string(n) + " particles");
  }
  if (!(cell_m > 0.0) || !std::isfinite(cell_m)) {
    throw std::invalid_argument("SpatialContactOrder: cell size must be positive and finite");
  }
  // Particles along the Morton curve of their cells (cells counted from the lowest corner,
  // 2^21 per axis at most: farther particles share the last cell, which only costs locality).
  Eigen::Vector3d low = n > 0 ? position_m[0] : Eigen::Vector3d::Zero();
  for (const auto& x : position_m) low = low.cwiseMin(x);
  keys_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double cell = std::floor((position_m[p][a] - low[a]) / cell_m);
      const auto c = static_cast<std::uint64_t>(std::clamp(cell, 0.0, double((1 << 21) - 1)));
      code |= spread_bits(c) << a;
    }
    keys_[p] = {code, static_cast<std::int32_t>(p)};
  }
  std::sort(keys_.begin(), keys_.end());
  number_.resize(n);
  for (std::size_t k = 0; k < n; ++k) number_[static_cast<std::size_t>(keys_[k].second)] = static_cast<std::int32_t>(k);

  // Contacts by (smaller number, then walls by index, then the larger number): unique keys,
  // since the problem has one contact per pair.
  const std::size_t contacts = problem.size();
  const std::uint64_t walls = problem.body_count() - n;
  const std::uint64_t stride = n + walls;
  keys_.resize(contacts);
  for (std::size_t c = 0; c < contacts; ++c) {
    const auto i = static_cast<std::uint64_t>(number_[static_cast<std::size_t>(problem.body_i[c])]);
    const std::int32_t j = problem.body_j[c];
    std::uint64_t first = i, second;
    if (is_wall(j)) {
      second = wall_index(j);
    } else {
      const auto other = static_cast<std::uint64_t>(number_[static_cast<std::size_t>(j)]);
      first = std::min(i, other);
      second = walls + std::max(i, other);
    }
    keys_[c] = {first * stride + second, static_cast<std::int32_t>(c)};
  }
  std::sort(keys_.begin(), keys_.end());
  order_.resize(contacts);
  for (std::size_t k = 0; k < contacts; ++k) order_[k] = keys_[k].second;
  valid_ = true;
}

void SpatialContactOrder::gather(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                                 const std::vector<Eigen::Vector3d>& m) {
  const std::size_t n = problem.particle_count, bodies = problem.body_count();
  ContactProblem& q = ordered_;
  q.dimension = problem.dimension;
  q.particle_count = n;
  q.rolling = problem.rolling;
  q.compliant = problem.compliant;
  q.stop_speed = problem.stop_speed;
  q.inverse_mass.resize(bodies);
  q.inverse_inertia.resize(bodies);
  q.free_velocity.resize(bodies);
  q.free_angular_velocity.resize(bodies);
  for (std::size_t b = 0; b < bodies; ++b) {
    const std::size_t to = b < n ? static_cast<std::size_t>(number_[b]) : b;  // walls stay
    q.inverse_mass[to] = problem.inverse_mass[b];
    q.inverse_inertia[to] = problem.inverse_inertia[b];
    q.free_velocity[to] = problem.free_velocity[b];
    q.free_angular_velocity[to] = problem.free_angular_velocity[b];
  }
  // The positions too, for a solver that cuts the contacts into slabs (ContactSlabs.h).
  q.split_axis = problem.split_axis;
  q.split_period = problem.split_period;
  q.particle_position.resize(problem.particle_position.size() == n ? n : 0);
  for (std::size_t p = 0; p < q.particle_position.size(); ++p)
    q.particle_position[static_cast<std::size_t>(number_[p])] = problem.particle_position[p];
  const std::size_t contacts = problem.size();
  q.resize_contacts(contacts);
  r_.resize(contacts);
  if (problem.rolling) m_.resize(contacts);
  const auto count = static_cast<std::ptrdiff_t>(contacts);
  // One slot each: the same bits for any thread count.
#pragma omp parallel for schedule(static) if (count >= parallel_from_)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto c = static_cast<std::size_t>(order_[static_cast<std::size_t>(k)]);
    const std::int32_t j = problem.body_j[c];
    q.copy_contact(static_cast<std::size_t>(k), problem, c);
    q.body_i[k] = number_[static_cast<std::size_t>(problem.body_i[c])];
    q.body_j[k] = is_wall(j) ? j : number_[static_cast<std::size_t>(j)];
    r_[k] = r[c];
    if (problem.rolling) m_[k] = m[c];
  }
}

SolveReport SpatialContactOrder::solve(ContactSolver& solver, const ContactProblem& problem,
                                       std::vector<Eigen::Vector3d>& r,
                                       std::vector<Eigen::Vector3d>& m,
                                       std::vector<Eigen::Vector3d>& velocity,
                                       std::vector<Eigen::Vector3d>& angular_velocity) {
  if (!valid_ || order_.size() != problem.size() || number_.size() != problem.particle_count) {
    throw std::logic_error("SpatialContactOrder::solve: the order does not fit the problem (update() first)");
  }
  gather(problem, r, m);
  const SolveReport report = solver.solve_with_rolling(ordered_, r_, m_, velocity_, angular_velocity_);
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
#pragma omp parallel for schedule(static) if (count >= parallel_from_)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto c = static_cast<std::size_t>(order_[static_cast<std::size_t>(k)]);
    r[c] = r_[k];
    if (problem.rolling) m[c] = m_[k];
  }
  const std::size_t n = problem.particle_count, bodies = problem.body_count();
  velocity.resize(bodies);
  angular_velocity.resize(bodies);
  for (std::size_t b = 0; b < bodies; ++b) {
    const std::size_t from = b < n ? static_cast<std::size_t>(number_[b]) : b;
    velocity[b] = velocity_[from];
    angular_velocity[b] = angular_velocity_[from];
  }
  return report;
}

}  // namespace tmdem::mechanics
