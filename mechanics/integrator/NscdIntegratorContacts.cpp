// NscdIntegrator's candidates and their contact problem, each step: the detector's refresh with
// the warm-start forces carried to the new table, then every candidate's geometry, Delassus
// block, friction, position term and warm start (setup_contacts). Moved out of
// NscdIntegrator.cpp as it was, operation for operation (the same bits).
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {
namespace {

// Two unit tangents completing n. In 2D, t1 stays in the plane and t2 = z, so that the
// out-of-plane tangential reaction is exactly zero.
void tangent_frame(const Eigen::Vector3d& n, int dimension, Eigen::Vector3d& t1,
                   Eigen::Vector3d& t2) {
  if (dimension == 2) {
    t1 = Eigen::Vector3d(-n.y(), n.x(), 0.0);
    t2 = Eigen::Vector3d::UnitZ();
    return;
  }
  const Eigen::Vector3d a =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  t1 = (a - a.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

// Per-candidate values onto a rebuilt table: values[k] = old[previous[k]] for a pair that stays a
// candidate (previous: ContactDetector::previous_index), `none` for a new one or one the old
// values did not reach (a table restored without torques); `old` keeps the vector for reuse.
template <class T>
void carry_over(std::vector<T>& values, std::vector<T>& old, const std::vector<std::int32_t>& previous,
                const T& none) {
  std::swap(values, old);
  values.resize(previous.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const bool kept = previous[k] >= 0 && std::size_t(previous[k]) < old.size();
    values[k] = kept ? old[static_cast<std::size_t>(previous[k])] : none;
  }
}

}  // namespace

void NscdIntegrator::fill_periodic_lookahead(double h) {
  // The look-ahead's bound on the motion across the periods, which alone decides whether a
  // second image could come into reach (ContactDetector.h): a bed pressed along its one walled
  // axis moves fast along it, hardly across.
  const PeriodicBox& box = particles_.box;
  periodic_lookahead_.resize(particles_.size());  // allocates once
  const double g_across = box.norm_across(gravity_);
  for (std::size_t i = 0; i < particles_.size(); ++i)
    periodic_lookahead_[i] = 2.0 * h * (box.norm_across(particles_.velocity[i]) + h * g_across);
}

void NscdIntegrator::fill_lookahead(double h) {
  // Look-ahead: a bound on the displacement during the coming step, doubled for the
  // contact impulses and the (1 - theta) part of the next position term.
  const double g = gravity_.norm();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    lookahead_[i] = 2.0 * h * (particles_.velocity[i].norm() + h * g);
  }
}

void NscdIntegrator::relist_with_bound(double h) {
  // A table listed anew from where the step starts, with the bound: what it would have been.
  detector_.invalidate();
  refresh_candidates(h, true);
}

void NscdIntegrator::refresh_candidates(double h, bool bound_only) {
  fill_lookahead(h);
  listing_estimated_ = false;
  // Not on a step whose start the static warm start or imported overlaps set up (they are taken
  // once, at the first set-up), nor without a last step's forces to estimate from.
  if (!bound_only && has_piston_ && parameters_.estimate_wall_reach && !static_start_pending_ &&
      holds_overlap_.empty())
    estimate_wall_reach(h);
  const auto& wall_reach = listing_estimated_ ? wall_listing_lookahead_ : wall_lookahead_;
  if (!detector_.update(particles_, walls_, lookahead_, wall_reach, periodic_lookahead_)) return;
  order_.invalidate();
  // Carry what pairs that stay candidates hold over to the new table: the forces (warm start),
  // the held overlaps and the rolling torques.
  const auto& previous = detector_.previous_index();
  carry_over(force_, old_force_, previous, Eigen::Vector3d::Zero().eval());
  if (!held_overlap_.empty()) carry_over(held_overlap_, old_held_overlap_, previous, 0.0);
  if (rolling_) carry_over(torque_, old_torque_, previous, Eigen::Vector3d::Zero().eval());
}

void NscdIntegrator::setup_contacts(double h) {
  const auto& pairs = detector_.pairs();
  const double theta = parameters_.theta;
  ContactProblem& p = problem_;
  p.resize_contacts(pairs.size());
  reactions_.resize(pairs.size());
  if (rolling_) {
    rolling_impulse_.resize(pairs.size());
    torque_.resize(pairs.size(), Eigen::Vector3d::Zero());  // a table restored without torques
  }
  gap_.resize(pairs.size());
  // Every candidate writes only its own entries: the same bits for any thread count.
  const bool periodic = particles_.box.any();  // hoisted: the open case stays x_i - x_j
#pragma omp parallel for schedule(static) \
    if (static_cast<std::ptrdiff_t>(pairs.size()) >= parameters_.parallel_from)
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::int32_t i = pairs[k].i, j = pairs[k].j;
    p.body_i[k] = i;
    p.body_j[k] = j;
    const Eigen::Vector3d& xi = particles_.position[i];
    const double lever_i = particles_.radius[i];
    double lever_j = 0.0;
    double inverse_mass = inverse_mass_[i];
    double inverse_rotation = lever_i * lever_i * inverse_inertia_[i];
    int other_material;
    Eigen::Vector3d n;
    double gap;
    if (!is_wall(j)) {
      const Eigen::Vector3d d = periodic ? particles_.box.minimum_image(xi - particles_.position[j])
                                         : Eigen::Vector3d(xi - particles_.position[j]);
      const double distance = d.norm();
      // Coincident centres have no defined normal; any unit vector in the plane will do.
      n = distance > 0.0 ? Eigen::Vector3d(d / distance) : Eigen::Vector3d::UnitY();
      // 2D: centres share z, so n_z is 0 already; enforce it if a scene breaks that.
      if (dimension_ == 2 && n.z() != 0.0) {
        n.z() = 0.0;
        n = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitY();
      }
      lever_j = particles_.radius[j];
      gap = distance - lever_i - lever_j;
      inverse_mass += inverse_mass_[j];
      inverse_rotation += lever_j * lever_j * inverse_inertia_[j];
      other_material = particles_.material[j];
    } else {
      const Wall& wall = walls_[wall_index(j)];
      n = wall.normal_at(xi);
      gap = wall.signed_distance(xi) - lever_i;
      other_material = wall.material;
      inverse_mass += p.inverse_mass[p.wall_body(j)];  // 0 unless a piston
    }
    p.normal[k] = n;
    p.lever_i[k] = lever_i;
    p.lever_j[k] = lever_j;
    gap_[k] = gap;
    tangent_frame(n, dimension_, p.tangent1[k], p.tangent2[k]);
    // W = H^T M^-1 H: (1/m_i + 1/m_j) I + (R_i^2/I_i + R_j^2/I_j) (I - n n^T), i.e.
    // diag(w_n, w_t, w_t) in the local frame.
    p.w_n[k] = inverse_mass;
    p.w_t[k] = inverse_mass + inverse_rotation;
    // Out of reach this step (NscdParameters::skip_out_of_reach): the detector lists pairs for
    // several steps (its margin, up to 2 radii while particles are fast), but within this one a
    // pair can close only by the two look-aheads, the bound the detector itself trusts. Such a
    // candidate leaves the problem (unsolvable) and the sweeps skip it.
    if (parameters_.skip_out_of_reach) {
      const double wall_ahead_m =
          is_wall(j) && !wall_lookahead_.empty() ? wall_lookahead_[wall_index(j)] : 0.0;
      const double reach_m = lookahead_[i] + (is_wall(j) ? wall_ahead_m : lookahead_[j]);
      if (gap > reach_m) p.w_n[k] = 0.0;
    }
    const double mu = contact_friction(materials_[particles_.material[i]], materials_[other_material]);
    p.mu[k] = mu;

    // Position term P / h, with the normal velocity at the start of the step.
    const Eigen::Vector3d u_old = relative_velocity<Eigen::Vector3d, VelocityRounding::points_first>(
        p, k, old_velocity_, old_angular_velocity_);
    // Activation by predicted gap only: an overlap is never turned into a push-out speed
    // (U_n = u_n there); the position step removes it (PenetrationCorrection.h).
    const double predicted = gap + h * (1.0 - theta) * u_old.dot(n);
    p.bias[k] = std::max(predicted, 0.0) / h;

    // Warm start: last step's force of this pair, in the new frame, as an impulse.
    // A step longer than the last (the first whole step after a landing taken in parts) starts
    // from the last step's impulses, not from its mean forces over the longer step: a part's
    // force is its impact's impulse over a sixteenth of a step, and 16 times that impulse threw
    // a landed piston back up where the solver stopped short of undoing it.
    // (A dynamic run's steps differ from one another by round-off: those keep force * h.)
    const double last_s = stats_.last_step_s;
    const Eigen::Vector3d impulse = force_[k] * (last_s > 0.0 && last_s < h * (1.0 - 1e-9) ? last_s : h);
    const Eigen::Vector3d r(impulse.dot(n), impulse.dot(p.tangent1[k]),
                            dimension_ == 2 ? 0.0 : impulse.dot(p.tangent2[k]));
    reactions_[k] = p.solvable(k) ? project_onto_coulomb_cone(r, mu) : Eigen::Vector3d::Zero();
    if (rolling_) {
      // R_eff = R_i R_j / (R_i + R_j), a wall R_i; w_r = 1/I_i + 1/I_j (walls do not turn).
      const double radius = lever_j > 0.0 ? lever_i * lever_j / (lever_i + lever_j) : lever_i;
      p.rolling_radius[k] = radius;
      p.rolling_limit[k] = radius * contact_rolling_friction(materials_[particles_.material[i]],
                                                             materials_[other_material]);
      p.w_r[k] = inverse_inertia_[i] + (is_wall(j) ? 0.0 : inverse_inertia_[j]);
      // Warm start: last step's torque, perpendicular to the new n, within the rolling cone.
      Eigen::Vector3d m = torque_[k] * h;
      m -= m.dot(n) * n;
      if (dimension_ == 2) m.x() = m.y() = 0.0;
      const double limit = p.rolling_limit[k] * reactions_[k][0];
      if (m.norm() > limit) m *= m.norm() > 0.0 ? limit / m.norm() : 0.0;
      rolling_impulse_[k] = p.solvable(k) && p.w_r[k] > 0.0 ? m : Eigen::Vector3d::Zero();
    }
  }
}

}  // namespace tmdem::mechanics
