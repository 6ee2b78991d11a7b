#include "mechanics/solvers/BodyContactBlock.h"

#include <Eigen/LU>
#include <cmath>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"

namespace tmdem::mechanics {
namespace {

// No regularisation of the stick rows: a hyperstatic block (e.g. a sphere stuck in a corner:
// more stick rows than the body's 6 velocities) gives a singular or near-singular system, whose
// non-finite or inexact answer the acceptance test below turns into single visits. A Tikhonov
// term of 1e-10 of the diagonal instead kept the settled pile of the rest tests creeping at
// 3e-8 m/s (moved 2e-7 m in 10,000 steps; 0 and 1e-14: at rest), measured.
constexpr double kAcceptance = 1e-9;   // single-visit change / block impulse for a solution
constexpr double kDirectionChange = 1e-10;

}  // namespace

BodyContactBlock::Result BodyContactBlock::solve(const ContactProblem& problem, std::size_t body,
                                                 const std::int32_t* contacts, int count,
                                                 std::vector<Eigen::Vector3d>& r,
                                                 std::vector<Eigen::Vector3d>& velocity,
                                                 std::vector<Eigen::Vector3d>& angular_velocity) {
  using Eigen::Vector3d;
  Result result;
  const bool planar = problem.dimension == 2;
  const auto n = static_cast<std::size_t>(count);
  jacobian_.resize(n);
  q_.resize(n);
  x_.resize(n);
  u_.resize(n);
  dir_.resize(n);
  status_.resize(n);
  slot_.resize(n);
  slip_gain_.assign(n, 0.0);
  coupling_.resize(9 * n * n);
  auto w_block = [&](std::size_t k, std::size_t l) {
    return Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&coupling_[9 * (k * n + l)]);
  };

  // Local velocity of contact c from the body's (v, omega): the rows of H_c^T for the side the
  // body is on (ContactKinematics.h, contact_rows).
  const double inverse_mass = problem.inverse_mass[body], inverse_inertia = problem.inverse_inertia[body];
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = static_cast<std::size_t>(contacts[k]);
    const bool is_i = static_cast<std::size_t>(problem.body_i[c]) == body;
    jacobian_[k] = contact_rows(problem, c, is_i ? 0 : 1);
    u_[k] = local_velocity<Vector3d>(problem, c, velocity, angular_velocity);
  }
  // Nothing to solve when every contact is unloaded and opening (most of a falling body's
  // candidates): the single visits would leave them at zero too.
  bool idle = true;
  for (std::size_t k = 0; k < n && idle; ++k) idle = r[contacts[k]][0] <= 0.0 && u_[k][0] >= 0.0;
  if (idle) {
    result.solved = true;
    return result;
  }
  Eigen::Matrix<double, 6, 1> mobility;
  mobility << inverse_mass, inverse_mass, inverse_mass, inverse_inertia, inverse_inertia, inverse_inertia;
  // W's columns are built when first needed: those of loaded or closed contacts (the others
  // multiply zero reactions).
  column_built_.assign(n, 0);
  auto build_column = [&](std::size_t l) {
    if (column_built_[l]) return;
    column_built_[l] = 1;
    const std::size_t c = static_cast<std::size_t>(contacts[l]);
    const Eigen::Matrix<double, 6, 3> mobile_l = mobility.asDiagonal() * jacobian_[l].transpose();
    for (std::size_t k = 0; k < n; ++k) {
      if (k == l) {
        w_block(l, l) = Eigen::Vector3d(problem.w_n[c], problem.w_t[c], planar ? 0.0 : problem.w_t[c]).asDiagonal();
      } else {
        w_block(k, l) = jacobian_[k] * mobile_l;
      }
    }
  };
  // q: the block's local velocities with its own reactions removed.
  for (std::size_t k = 0; k < n; ++k) q_[k] = u_[k];
  for (std::size_t l = 0; l < n; ++l) {
    const Vector3d& rl = r[contacts[l]];
    if (rl[0] == 0.0 && rl[1] == 0.0 && rl[2] == 0.0) continue;
    build_column(l);
    for (std::size_t k = 0; k < n; ++k) q_[k] -= w_block(k, l) * rl;
  }

  // Statuses from the warm start: a loaded contact sticks or slips as its reaction says, an
  // unloaded one is closed (stick) when it approaches.
  for (std::size_t k = 0; k < n; ++k) {
    const Vector3d& rc = r[contacts[k]];
    const double mu = problem.mu[contacts[k]];
    const double rt = std::hypot(rc[1], rc[2]);
    if (rc[0] > 0.0) {
      if (rt > 0.0 && rt >= mu * rc[0] * (1.0 - 1e-12)) {
        status_[k] = Status::slip;
        dir_[k] = Vector3d(0.0, rc[1] / rt, rc[2] / rt);
      } else {
        status_[k] = mu == 0.0 ? Status::slip : Status::stick;
        dir_[k].setZero();
      }
    } else {
      status_[k] = u_[k][0] < 0.0 ? Status::stick : Status::open;
      dir_[k].setZero();
    }
  }

  Matrix a;
  Vector b, solution;
  bool settled = false;
  while (result.passes < kMaxPasses && !settled) {
    ++result.passes;
    int closed = 0;
    for (std::size_t k = 0; k < n; ++k) {
      slot_[k] = status_[k] == Status::open ? -1 : closed++;
      if (slot_[k] >= 0) build_column(k);
    }
    if (closed > kMaxClosed) return Result{};
    // Unknowns per closed contact: (n, t1, t2), or (n, t1) in 2D (t2 stays 0).
    const int per = planar ? 2 : 3;
    const int size = per * closed;
    a.setZero(size, size);
    b.setZero(size);
    for (std::size_t k = 0; k < n; ++k) {
      if (slot_[k] < 0) continue;
      const int row = per * slot_[k];
      const double mu = problem.mu[contacts[k]];
      // Velocity rows: u_c = q_c + sum_l W_cl x_l = 0 (all three for stick, the normal for slip).
      const int velocity_rows = status_[k] == Status::stick ? per : 1;
      for (std::size_t l = 0; l < n; ++l) {
        if (slot_[l] < 0) continue;
        a.block(row, per * slot_[l], velocity_rows, per) = w_block(k, l).topLeftCorner(velocity_rows, per);
      }
      for (int i = 0; i < velocity_rows; ++i) b[row + i] = -q_[k][i];
      // Friction rows of a slip, r_t = mu r_n d(u_t) with d = -u_t / |u_t|, linearised at the
      // previous pass (r_n0, u_t0 = -|u_t0| d0) as in a semismooth Newton step:
      //   x_t - mu d0 x_n + (mu r_n0 / |u_t0|) (I - d0 d0^T) u_t = 0,   u_t = q_t + W_t x,
      // (the fixed-direction iteration, without the last term, cycles when two slipping contacts
      // turn the body between them).
      for (int i = velocity_rows; i < per; ++i) {
        a(row + i, row + i) = 1.0;
        if (status_[k] == Status::slip) a(row + i, row) = -mu * dir_[k][i];
      }
      if (status_[k] == Status::slip && slip_gain_[k] > 0.0 && !planar) {
        const Eigen::Vector3d& d = dir_[k];
        Eigen::Matrix3d project = Eigen::Matrix3d::Zero();  // (I - d d^T) on the tangent plane
        project(1, 1) = 1.0 - d[1] * d[1];
        project(2, 2) = 1.0 - d[2] * d[2];
        project(1, 2) = project(2, 1) = -d[1] * d[2];
        const Eigen::Matrix3d gain = slip_gain_[k] * project;
        for (std::size_t l = 0; l < n; ++l) {
          if (slot_[l] < 0) continue;
          a.block(row + 1, per * slot_[l], 2, 3) += (gain * w_block(k, l)).bottomRows(2);
        }
        b.segment<2>(row + 1) -= (gain * q_[k]).tail<2>();
      }
    }
    if (size > 0) {
      solution = a.partialPivLu().solve(b);
      if (!solution.allFinite()) return Result{};
    }
    for (std::size_t k = 0; k < n; ++k) {
      x_[k].setZero();
      if (slot_[k] >= 0) x_[k].head(per) = solution.segment(per * slot_[k], per);
    }
    for (std::size_t k = 0; k < n; ++k) {
      u_[k] = q_[k];
      for (std::size_t l = 0; l < n; ++l) {
        if (slot_[l] >= 0) u_[k] += w_block(k, l) * x_[l];
      }
      if (planar) u_[k][2] = 0.0;
    }
    // Status switches where the law is violated.
    settled = true;
    for (std::size_t k = 0; k < n; ++k) {
      const double mu = problem.mu[contacts[k]];
      const Vector3d& x = x_[k];
      const Vector3d& u = u_[k];
      if (status_[k] == Status::open) {
        if (u[0] < 0.0) {
          status_[k] = mu == 0.0 ? Status::slip : Status::stick;
          settled = false;
        }
      } else if (x[0] < 0.0) {
        status_[k] = Status::open;
        settled = false;
      } else if (mu == 0.0) {
        continue;  // frictionless: x_t = 0 whatever the direction
      } else if (status_[k] == Status::stick) {
        const double rt = std::hypot(x[1], x[2]);
        if (rt > mu * x[0] * (1.0 + 1e-12)) {
          status_[k] = Status::slip;
          dir_[k] = Vector3d(0.0, x[1] / rt, x[2] / rt);
          slip_gain_[k] = 0.0;  // no slip velocity yet: a fixed-direction pass first
          settled = false;
        }
      } else {
        const double ut = std::hypot(u[1], u[2]);
        if (ut == 0.0 || u[1] * dir_[k][1] + u[2] * dir_[k][2] > 0.0) {
          status_[k] = Status::stick;  // no slip, or slipping along the friction: stick
          settled = false;
        } else {
          const Vector3d next(0.0, -u[1] / ut, -u[2] / ut);
          if ((next - dir_[k]).norm() > kDirectionChange) {
            dir_[k] = next;
            settled = false;
          }
          slip_gain_[k] = mu * x[0] / ut;
        }
      }
    }
  }

  // Acceptance: each contact's own closed-form visit leaves it (nearly) where it is.
  double change = 0.0, total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = static_cast<std::size_t>(contacts[k]);
    const double w_n = problem.w_n[c], w_t = problem.w_t[c];
    const Vector3d u0(u_[k][0] - w_n * x_[k][0], u_[k][1] - w_t * x_[k][1],
                      planar ? 0.0 : u_[k][2] - w_t * x_[k][2]);
    Vector3d single;
    solve_contact_bipotential(u0, w_n, w_t, problem.mu[c], single);
    if (planar) single[2] = 0.0;
    change += (single - x_[k]).norm();
    total += single.norm();
    x_[k] = single;  // the same to 1e-9 if accepted, and exactly in its cone
  }
  if (!(change <= kAcceptance * total)) return Result{};

  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = static_cast<std::size_t>(contacts[k]);
    const Vector3d dr = x_[k] - r[c];
    if (dr[0] != 0.0 || dr[1] != 0.0 || dr[2] != 0.0) {
      apply_impulse(problem, c, dr, velocity, angular_velocity);
      r[c] = x_[k];
    }
    result.update.change += dr.norm();
    result.update.total += x_[k].norm();
  }
  result.solved = true;
  return result;
}

}  // namespace tmdem::mechanics
