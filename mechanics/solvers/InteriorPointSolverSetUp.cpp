// InteriorPointSolver (InteriorPointSolver.h): the set-up of a solve, apart from its iteration.
// set_up builds the degrees of freedom, each contact's columns and cones, and K's pattern with
// its analysis when the pattern is new; start turns the warm start (or, cold, the penalty
// point) into an interior starting point.
#include "mechanics/solvers/InteriorPointSolver.h"

#include <algorithm>
#include <cmath>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/solvers/InteriorPointFactor.h"
#include "mechanics/solvers/SecondOrderCone.h"

namespace tmdem::mechanics {

void InteriorPointSolver::set_up(const ContactProblem& problem) {
  planar_ = problem.dimension == 2;
  rolling_ = problem.rolling;
  const std::size_t bodies = problem.body_count(), contacts = problem.size();
  // Degrees of freedom: mobile particles, and pistons (a wall body with mass) along their normal.
  first_dof_.assign(bodies, -1);
  piston_normal_.assign(bodies, Eigen::Vector3d::Zero());
  for (std::size_t c = 0; c < contacts; ++c)
    if (is_wall(problem.body_j[c])) piston_normal_[problem.wall_body(problem.body_j[c])] = problem.normal[c];
  int dofs = 0;
  const int particle_dofs = planar_ ? 3 : 6;
  for (std::size_t b = 0; b < bodies; ++b) {
    if (!(problem.inverse_mass[b] > 0.0)) continue;
    if (b >= problem.particle_count && piston_normal_[b].squaredNorm() == 0.0) continue;
    first_dof_[b] = dofs;
    dofs += b < problem.particle_count ? particle_dofs : 1;
  }
  mass_.resize(dofs);
  for (std::size_t b = 0; b < bodies; ++b) {
    const int f = first_dof_[b];
    if (f < 0) continue;
    const double mass = 1.0 / problem.inverse_mass[b];
    if (b >= problem.particle_count) {
      mass_[f] = mass;
      continue;
    }
    const double inertia = problem.inverse_inertia[b] > 0.0 ? 1.0 / problem.inverse_inertia[b] : 0.0;
    for (int k = 0; k < (planar_ ? 2 : 3); ++k) mass_[f + k] = mass;
    for (int k = planar_ ? 2 : 3; k < particle_dofs; ++k) mass_[f + k] = inertia;
  }
  columns_.resize(contacts);
  for (auto* v : {&dim_f_, &dim_r_}) v->assign(contacts, 0);
  for (auto* v : {&sigma_f_, &sigma_r_, &mu_, &rolling_limit_, &slip_, &load_, &t_, &rt_, &dt_, &ktt_, &rhs_t_})
    v->assign(contacts, 0.0);
  for (auto* v : {&q_, &q_roll_, &h_f_, &h_r_, &s_f_, &z_f_, &s_r_, &z_r_, &rz_f_, &rz_r_, &ds_f_, &dz_f_, &ds_r_,
                  &dz_r_, &ds_fa_, &dz_fa_, &ds_ra_, &dz_ra_, &lambda_f_, &lambda_r_, &xi_f_, &xi_r_, &y_f_, &y_r_})
    v->assign(contacts, Eigen::Vector3d::Zero());
  for (auto* v : {&w_f_, &w_r_, &winv_f_, &winv_r_, &w2_f_, &w2_r_}) v->assign(contacts, Eigen::Matrix3d::Zero());
  b_t_.assign(contacts, Eigen::Matrix<double, kMaxDofs, 1>::Zero());
  pattern_key_.clear();
  pattern_key_.push_back(dofs);
  for (std::size_t c = 0; c < contacts; ++c) {
    Columns& col = columns_[c];
    col.count = 0;
    if (!problem.solvable(c)) continue;
    const Eigen::Vector3d n = problem.normal[c], t1 = problem.tangent1[c], t2 = problem.tangent2[c];
    const Eigen::Matrix3d perp = Eigen::Matrix3d::Identity() - n * n.transpose();
    auto add = [&](std::int32_t dof, const Eigen::Vector3d& g, const Eigen::Vector3d& roll) {
      col.dof[col.count] = dof;
      col.g[col.count] = g;
      // The rolling rows in the frame (t1, t2); in the plane the spin is along z = t2.
      col.rolling[col.count] =
          planar_ ? Eigen::Vector3d(0.0, roll.dot(t2), 0.0) : Eigen::Vector3d(0.0, roll.dot(t1), roll.dot(t2));
      ++col.count;
    };
    // A particle's columns of U_c per unknown: the rows of H_c^T the sweeps apply
    // (ContactKinematics.h, contact_rows; in the plane its t2 row is zero, which the plane's
    // cones never read), column by column: v_x, v_y (, v_z), then the spins (the plane: omega_z).
    auto add_particle = [&](std::size_t b, int side) {
      const int f = first_dof_[b];
      if (f < 0) return;
      const Eigen::Matrix<double, 3, 6> rows = contact_rows(problem, c, side);
      const double sign = side == 0 ? 1.0 : -1.0;
      const int linear = planar_ ? 2 : 3;
      for (int k = 0; k < linear; ++k) add(f + k, rows.col(k), Eigen::Vector3d::Zero());
      for (int k = planar_ ? 2 : 0; k < 3; ++k) add(planar_ ? f + 2 : f + linear + k, rows.col(3 + k), sign * perp.col(k));
    };
    const std::int32_t i = problem.body_i[c], j = problem.body_j[c];
    add_particle(i, 0);
    std::int64_t other = -1;
    if (!is_wall(j)) {
      add_particle(j, 1);
      other = first_dof_[j];
    } else if (const std::size_t b = problem.wall_body(j); first_dof_[b] >= 0) {
      const Eigen::Vector3d& N = piston_normal_[b];
      add(first_dof_[b], -Eigen::Vector3d(n.dot(N), t1.dot(N), t2.dot(N)), Eigen::Vector3d::Zero());
      other = first_dof_[b];
    }
    if (col.count == 0) continue;
    pattern_key_.push_back((static_cast<std::int64_t>(first_dof_[i]) << 32) ^ (other & 0xffffffff));
    mu_[c] = problem.mu[c];
    dim_f_[c] = mu_[c] > 0.0 ? (planar_ ? 2 : 3) : 1;
    sigma_f_[c] = 1.0 / std::sqrt(problem.w_n[c]);
    for (int k = 0; k < col.count; ++k) {
      const Eigen::Vector3d& g = col.g[k];
      col.friction[k] = dim_f_[c] == 1 ? Eigen::Vector3d(g[0], 0.0, 0.0)
                                       : Eigen::Vector3d(g[0] / mu_[c], g[1], planar_ ? 0.0 : g[2]);
      col.friction[k] *= sigma_f_[c];
    }
    q_[c] = local_velocity<Eigen::Vector3d>(problem, c, problem.free_velocity, problem.free_angular_velocity);
    if (rolling_ && problem.rolling_limit[c] > 0.0 && problem.w_r[c] > 0.0) {
      dim_r_[c] = planar_ ? 2 : 3;
      sigma_r_[c] = 1.0 / std::sqrt(problem.w_r[c]);
      rolling_limit_[c] = problem.rolling_limit[c];
      for (int k = 0; k < col.count; ++k) col.rolling[k] *= sigma_r_[c];
      const Eigen::Vector3d spin =
          rolling_velocity<Eigen::Vector3d>(problem, c, problem.free_angular_velocity);
      q_roll_[c] = planar_ ? Eigen::Vector3d(0.0, spin.dot(t2), 0.0)
                           : Eigen::Vector3d(0.0, spin.dot(t1), spin.dot(t2));
    }
  }
  dv_.setZero(dofs);
  rx_.setZero(dofs);
  rhs_.setZero(dofs);
  ddv_.setZero(dofs);
  if (pattern_key_ == last_key_) return;
  // A new pattern: K's lower triangle (explicit zeros where a contact is open), its analysis,
  // and where each contact's entries sit among its values.
  triplets_.clear();
  for (int d = 0; d < dofs; ++d) triplets_.emplace_back(d, d, 0.0);
  for (std::size_t c = 0; c < contacts; ++c) {
    const Columns& col = columns_[c];
    for (int l = 0; l < col.count; ++l)
      for (int k = 0; k < col.count; ++k)
        if (col.dof[l] > col.dof[k]) triplets_.emplace_back(col.dof[l], col.dof[k], 0.0);
  }
  matrix_.resize(dofs, dofs);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  matrix_.makeCompressed();
  auto slot = [&](std::int32_t row, std::int32_t column) -> std::int64_t {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[column];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[column + 1];
    return std::lower_bound(begin, end, row) - matrix_.innerIndexPtr();
  };
  diagonal_slot_.resize(dofs);
  for (int d = 0; d < dofs; ++d) diagonal_slot_[d] = slot(d, d);
  block_slot_.assign(contacts * kMaxDofs * kMaxDofs, -1);
  for (std::size_t c = 0; c < contacts; ++c) {
    const Columns& col = columns_[c];
    for (int l = 0; l < col.count; ++l)
      for (int k = 0; k < col.count; ++k)
        if (col.dof[l] >= col.dof[k]) block_slot_[(c * kMaxDofs + l) * kMaxDofs + k] = slot(col.dof[l], col.dof[k]);
  }
  factor_->llt.analyzePattern(matrix_);
  last_key_ = pattern_key_;
  ++analyses_;
}

void InteriorPointSolver::start(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                                const std::vector<Eigen::Vector3d>& velocity,
                                const std::vector<Eigen::Vector3d>& angular_velocity) {
  for (std::size_t b = 0; b < first_dof_.size(); ++b) {
    const int f = first_dof_[b];
    if (f < 0) continue;
    const Eigen::Vector3d dlin = velocity[b] - problem.free_velocity[b];
    if (b >= problem.particle_count) {
      dv_[f] = dlin.dot(piston_normal_[b]);
      continue;
    }
    const Eigen::Vector3d dang = angular_velocity[b] - problem.free_angular_velocity[b];
    if (planar_) {
      dv_[f] = dlin[0];
      dv_[f + 1] = dlin[1];
      dv_[f + 2] = dang[2];
    } else {
      dv_.segment<3>(f) = dlin;
      dv_.segment<3>(f + 3) = dang;
    }
  }
  // The law of this convex problem (slip, rolling limits) from the given velocities and
  // reactions, then its penalty point.
  freeze_law(r);
  int cones = 0;
  for (std::size_t c = 0; c < columns_.size(); ++c) cones += (dim_f_[c] > 0) + (dim_r_[c] > 0);
  // The penalty point: x minimising 1/2 x^T P x + c^T x + kappa/2 |h + A x|^2, with
  // z = -kappa s (K's matrix at W^2 = kappa I): a direct solve, so the multipliers already
  // carry the load through the depth (CVXOPT's start is kappa = 1). Why not the warm start:
  // near the solution it sits on the cones' boundary, and the shifts that bring it inside
  // took the residual of a tall column's steps from 1.5e-5 to 4e-4 in the first iteration.
  const double penalty = options_.start_penalty;
  double size = 0.0;
  if (cones > 0) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (dim_f_[c] == 0) continue;
      w_f_[c] = std::sqrt(penalty) * Eigen::Matrix3d::Identity();
      w2_f_[c] = penalty * Eigen::Matrix3d::Identity();
      xi_f_[c].setZero();
      rz_f_[c] = -h_f_[c];
      if (dim_r_[c] == 0) continue;
      w_r_[c] = std::sqrt(penalty) * Eigen::Matrix3d::Identity();
      w2_r_[c] = penalty * Eigen::Matrix3d::Identity();
      xi_r_[c].setZero();
      rz_r_[c] = -h_r_[c];
      rt_[c] = 0.0;
      t_[c] = 0.0;
    }
    dv_.setZero();
    rx_.setZero();
    if (assemble_and_factorise()) {
      direction(xi_f_, xi_r_);
      dv_ = ddv_;
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        if (dim_f_[c] == 0) continue;
        s_f_[c] = ds_f_[c];  // = A x + h: rz was -h
        z_f_[c] = -penalty * s_f_[c];
        size += s_f_[c].norm() + z_f_[c].norm();
        if (dim_r_[c] == 0) continue;
        t_[c] = dt_[c];
        s_r_[c] = ds_r_[c];
        z_r_[c] = -penalty * s_r_[c];
        size += s_r_[c].norm() + z_r_[c].norm();
      }
    }
  }
  // Into the cones' interior, balanced (Mehrotra's start for linear programs, with the cones'
  // smaller eigenvalue for the sign): both shifted past 1.5x their worst violation, then each by
  // half the gap over the other's size.
  double low_s = 0.0, low_z = 0.0;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    low_s = std::min(low_s, cone::smallest_eigenvalue(dim_f_[c], s_f_[c]));
    low_z = std::min(low_z, cone::smallest_eigenvalue(dim_f_[c], z_f_[c]));
    if (dim_r_[c] == 0) continue;
    low_s = std::min(low_s, cone::smallest_eigenvalue(dim_r_[c], s_r_[c]));
    low_z = std::min(low_z, cone::smallest_eigenvalue(dim_r_[c], z_r_[c]));
  }
  const double floor_value = 1e-12 * (cones > 0 && size > 0.0 ? size / cones : 1.0);
  const double shift_s = std::max(-1.5 * low_s, floor_value), shift_z = std::max(-1.5 * low_z, floor_value);
  double gap = 0.0, sum_s = 0.0, sum_z = 0.0;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    s_f_[c][0] += shift_s;
    z_f_[c][0] += shift_z;
    gap += s_f_[c].dot(z_f_[c]);
    sum_s += s_f_[c][0];
    sum_z += z_f_[c][0];
    if (dim_r_[c] == 0) continue;
    s_r_[c][0] += shift_s;
    z_r_[c][0] += shift_z;
    gap += s_r_[c].dot(z_r_[c]);
    sum_s += s_r_[c][0];
    sum_z += z_r_[c][0];
  }
  const double extra_s = 0.5 * gap / sum_z, extra_z = 0.5 * gap / sum_s;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    s_f_[c][0] += extra_s;
    z_f_[c][0] += extra_z;
    if (dim_r_[c] == 0) continue;
    s_r_[c][0] += extra_s;
    z_r_[c][0] += extra_z;
  }
}

}  // namespace tmdem::mechanics
