// NscdIntegrator's pistons, each step: their free velocities and the reach they are listed with
// (the bound, or the likely reach of a loaded piston the bed holds, checked against the step's
// travel after the solve), and whether a landing must be taken in parts. Moved out of
// NscdIntegrator.cpp and NscdIntegratorContacts.cpp as they were (the same bits).
#include <algorithm>
#include <cmath>

#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {

void NscdIntegrator::refresh_wall_bodies(double h) {
  // Wall bodies: start-of-step and free velocities along the normal (fixed walls stay at 0),
  // and how far a piston may move in the coming step (as for particles in refresh_candidates).
  const std::size_t n = particles_.size();
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const Wall& wall = walls_[w];
    if (!wall.moves()) continue;
    const double acceleration = piston_acceleration_m_per_s2(wall);
    old_velocity_[n + w] = wall.velocity_m_per_s * wall.normal;
    problem_.free_velocity[n + w] = (wall.velocity_m_per_s + h * acceleration) * wall.normal;
    wall_lookahead_[w] = 2.0 * h * (std::abs(wall.velocity_m_per_s) + h * std::abs(acceleration));
  }
}

bool NscdIntegrator::wall_lands_too_fast(double h) {
  // The look-aheads the engaged test reads are filled only for a wall fast enough: on the other
  // steps the step itself fills them once (refresh_wall_bodies, refresh_candidates).
  bool filled = false;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    if (!walls_[w].moves()) continue;
    // The reach of the wall's own speed, not its look-ahead: a piston resting on a bed under a
    // large load has a look-ahead of 2 h^2 F / m (what it would travel if nothing held it,
    // 1.3 mm for box_pressed's 12.5 N on 20 g), but brings no speed to hand on.
    const double speed_reach_m = 2.0 * h * std::abs(walls_[w].velocity_m_per_s);
    if (!detector_.wall_reach_exceeds_margin(speed_reach_m)) continue;
    if (!filled) {
      refresh_wall_bodies(h);
      fill_lookahead(h);
      filled = true;
    }
    if (detector_.wall_engaged(particles_, walls_[w], wall_lookahead_[w], lookahead_)) return true;
  }
  return false;
}

void NscdIntegrator::estimate_wall_reach(double h) {
  // The bed's push on each piston over the last step: the forces its candidates carried (the
  // warm start, force on the particle, so along the wall's normal into the domain).
  std::fill(wall_carried_N_.begin(), wall_carried_N_.end(), 0.0);
  const auto& pairs = detector_.pairs();
  for (std::size_t k = 0; k < pairs.size() && k < force_.size(); ++k)
    if (is_wall(pairs[k].j)) {
      const std::size_t w = wall_index(pairs[k].j);
      if (walls_[w].moves()) wall_carried_N_[w] += force_[k].dot(walls_[w].normal);
    }
  listing_estimated_ = false;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const Wall& wall = walls_[w];
    if (!wall.moves()) continue;
    // The bound wall_lookahead_ takes the whole load and weight as if nothing held the piston:
    // 2 h^2 F / m, 12.8 mm for 6.4 N on 1 g at h = 1 ms, against 1 mm spheres that the bed lets
    // it move by 0.05 mm; once engaged, every particle pair within it is listed (3.6 million
    // candidates for 2,920 spheres, 13 s a step). What the bed leaves of that push, doubled, is
    // the likely reach; the step's travel is checked against the table after the solve.
    // Only where the load alone makes the bound list dozens of candidates per particle (its
    // share 2 h^2 |a| beyond kEstimatedReachFrom widest margins, 4 largest radii; a fast piston's
    // own speed, which it may hand to the bed, stays in the bound): a smaller table also holds
    // fewer open candidates, whose gaps make most of the scale ||q|| of Siconos' residual, so the
    // same steps are judged more strictly and take more sweeps: estimated from half a widest
    // margin on, the 40-layer shaft at 1e4 Pa (load reach 1.28 mm, 2.6 radii) took 314 s
    // instead of 75 s (682 mean sweeps against 256). Above the threshold, piston_cylinder's
    // 1e5 Pa load (4.5 mm, 5 radii) took 41 s instead of 276 s, none unconverged either way
    // (docs/mechanics.md "A loaded piston's reach").
    wall_listing_lookahead_[w] = wall_lookahead_[w];
    const double acceleration = piston_acceleration_m_per_s2(wall);
    if (2.0 * h * h * std::abs(acceleration) <= kEstimatedReachFrom * detector_.max_margin()) continue;
    const double net_m_per_s2 = acceleration - wall_carried_N_[w] / wall.mass_kg;
    const double likely_m = 2.0 * h * (std::abs(wall.velocity_m_per_s) + 2.0 * h * std::abs(net_m_per_s2));
    wall_listing_lookahead_[w] = std::min(wall_lookahead_[w], likely_m);
    listing_estimated_ = listing_estimated_ || wall_listing_lookahead_[w] < wall_lookahead_[w];
  }
}

bool NscdIntegrator::listing_covers_travel(double h) {
  const std::size_t n = particles_.size();
  const double theta = parameters_.theta;
  travel_m_.resize(n);  // allocates once
  for (std::size_t i = 0; i < n; ++i)
    travel_m_[i] = inverse_mass_[i] == 0.0
                       ? Eigen::Vector3d::Zero().eval()
                       : Eigen::Vector3d(h * (theta * body_velocity_[i] + (1.0 - theta) * old_velocity_[i]));
  for (std::size_t w = 0; w < walls_.size(); ++w)
    wall_travel_m_[w] = walls_[w].moves() ? h * (theta * body_velocity_[n + w].dot(walls_[w].normal) +
                                                 (1.0 - theta) * walls_[w].velocity_m_per_s)
                                          : 0.0;
  return detector_.covers(particles_, travel_m_, walls_, wall_travel_m_);
}

}  // namespace tmdem::mechanics
