#include "mechanics/ApgdSolver.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "mechanics/CoulombCone.h"
#include "mechanics/FixedBlockSums.h"
#include "mechanics/NaturalMapResidual.h"

namespace tmdem::mechanics {
namespace {

constexpr std::ptrdiff_t kBlock = kSumBlock;  // FixedBlockSums.h

// Projection onto K_mu in the metric D = diag(w_n, w_t, w_t): the Euclidean projection of
// D^1/2 tau onto the scaled cone, mapped back.
Eigen::Vector3d project_in_metric(const Eigen::Vector3d& tau, double w_n, double w_t, double mu,
                                  bool planar) {
  const double sn = std::sqrt(w_n), st = std::sqrt(w_t);
  const Eigen::Vector3d z =
      project_onto_coulomb_cone(Eigen::Vector3d(tau[0] * sn, tau[1] * st, tau[2] * st), mu * st / sn);
  return Eigen::Vector3d(z[0] / sn, z[1] / st, planar ? 0.0 : z[2] / st);
}

double tangential_speed(const Eigen::Vector3d& u) { return std::hypot(u[1], u[2]); }

// Contact c's second body when it moves (a particle or a piston), none for a fixed wall.
std::optional<std::size_t> moving_body_j(const ContactProblem& problem, std::size_t c) {
  const std::int32_t j = problem.body_j[c];
  if (!is_wall(j)) return std::size_t(j);
  const std::size_t b = problem.wall_body(j);
  if (problem.inverse_mass[b] > 0.0) return b;
  return std::nullopt;
}

}  // namespace

ApgdSolver::ApgdSolver(const SolverSettings& settings, std::ptrdiff_t parallel_from)
    : settings_(settings), parallel_from_(parallel_from) {}

void ApgdSolver::build_body_lists(const ContactProblem& problem) {
  const std::size_t bodies = problem.body_count(), count = problem.size();
  body_start_.assign(bodies + 1, 0);
  for (std::size_t c = 0; c < count; ++c) {
    if (!problem.solvable(c)) continue;
    ++body_start_[problem.body_i[c] + 1];
    if (const auto j = moving_body_j(problem, c)) ++body_start_[*j + 1];
  }
  for (std::size_t b = 0; b < bodies; ++b) body_start_[b + 1] += body_start_[b];
  body_contact_.resize(static_cast<std::size_t>(body_start_[bodies]));
  body_fill_.assign(body_start_.begin(), body_start_.end() - 1);
  // Contact order within each body: the gather adds impulses in the order a sequential
  // apply_impulse loop would.
  for (std::size_t c = 0; c < count; ++c) {
    if (!problem.solvable(c)) continue;
    body_contact_[body_fill_[problem.body_i[c]]++] = static_cast<std::int32_t>(c);
    if (const auto j = moving_body_j(problem, c)) {
      body_contact_[body_fill_[*j]++] = -1 - static_cast<std::int32_t>(c);
    }
  }
}

void ApgdSolver::local_velocities(const ContactProblem& problem,
                                  const std::vector<Eigen::Vector3d>& x,
                                  std::vector<Eigen::Vector3d>& velocity,
                                  std::vector<Eigen::Vector3d>& angular_velocity,
                                  std::vector<Eigen::Vector3d>& u) {
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  const auto bodies = static_cast<std::ptrdiff_t>(problem.body_count());
  const auto particles = static_cast<std::ptrdiff_t>(problem.particle_count);
#pragma omp parallel if (count >= parallel_from_)
  {
#pragma omp for schedule(static)
    for (std::ptrdiff_t c = 0; c < count; ++c) {
      impulse_[c] = problem.to_global(static_cast<std::size_t>(c), x[c]);
      torque_arm_[c] = problem.normal[c].cross(impulse_[c]);
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t b = 0; b < bodies; ++b) {
      Eigen::Vector3d v = problem.free_velocity[b], w = problem.free_angular_velocity[b];
      const double inverse_mass = problem.inverse_mass[b], inverse_inertia = problem.inverse_inertia[b];
      for (std::int32_t k = body_start_[b]; k < body_start_[b + 1]; ++k) {
        const std::int32_t e = body_contact_[k];
        if (e >= 0) {  // body i: +p at x_i - R_i n
          v += inverse_mass * impulse_[e];
          w -= (inverse_inertia * problem.lever_i[e]) * torque_arm_[e];
        } else if (b < particles) {  // body j: -p at x_j + R_j n
          const std::int32_t c = -1 - e;
          v -= inverse_mass * impulse_[c];
          w -= (inverse_inertia * problem.lever_j[c]) * torque_arm_[c];
        } else {       // a piston: -r_n n, along its normal only
          const std::int32_t c = -1 - e;
          v -= (inverse_mass * x[c][0]) * problem.normal[c];
        }
      }
      velocity[b] = v;
      angular_velocity[b] = w;
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t c = 0; c < count; ++c) {
      u[c] = problem.local_velocity(static_cast<std::size_t>(c), velocity, angular_velocity);
    }
  }
}

SolveReport ApgdSolver::solve(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                              std::vector<Eigen::Vector3d>& velocity,
                              std::vector<Eigen::Vector3d>& angular_velocity) {
  const std::size_t count = problem.size();
  const auto n = static_cast<std::ptrdiff_t>(count);
  const bool planar = problem.dimension == 2;
  const std::ptrdiff_t blocks = sum_block_count(n);
  for (auto* v : {&x_, &x_old_, &y_, &ux_, &ux_old_, &uy_, &best_, &impulse_, &torque_arm_}) {
    v->resize(count);
  }
  slip_bias_.resize(count);
  partial_a_.resize(static_cast<std::size_t>(3 * blocks));
  partial_b_.resize(static_cast<std::size_t>(2 * blocks));
  velocity.resize(problem.body_count());
  angular_velocity.resize(problem.body_count());
  build_body_lists(problem);

  for (std::size_t c = 0; c < count; ++c) x_[c] = problem.solvable(c) ? r[c] : Eigen::Vector3d::Zero();
  local_velocities(problem, x_, velocity, angular_velocity, ux_);

  // Residual of x_ (from ux_) and the slip bias s = mu |u_t| it gives, in one pass.
  auto residual_and_slip = [&] {
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
    for (std::ptrdiff_t block = 0; block < blocks; ++block) {
      double defect = 0.0, total = 0.0;
      for (std::ptrdiff_t c = block * kBlock; c < std::min(n, (block + 1) * kBlock); ++c) {
        const auto cc = static_cast<std::size_t>(c);
        if (!problem.solvable(cc)) continue;
        slip_bias_[c] = problem.mu[c] * tangential_speed(ux_[c]);
        const Eigen::Vector3d next = local_law_solution(problem, cc, x_[c], ux_[c]);
        defect += (next - x_[c]).norm();
        total += next.norm();
      }
      partial_b_[2 * block] = defect;
      partial_b_[2 * block + 1] = total;
    }
    const auto [defect, total] = add_block_sums<2>(partial_b_, blocks);
    return natural_map_ratio(defect, total);
  };

  SolveReport report;
  double best_residual = residual_and_slip();
  int best_sweep = 0;
  best_.assign(x_.begin(), x_.end());
  y_.assign(x_.begin(), x_.end());
  uy_.assign(ux_.begin(), ux_.end());
  double theta = 1.0;
  // Stall watch, as nlgs: the sweep at which the best residual last fell by 10%.
  double progress = best_residual;
  int progress_sweep = 0;
  while (best_residual > settings_.tolerance && report.sweeps < settings_.max_iterations) {
    if (report.sweeps - progress_sweep >= settings_.stall_sweeps) {
      report.stalled = true;
      break;
    }
    ++report.sweeps;
    std::swap(x_, x_old_);
    std::swap(ux_, ux_old_);
    double lipschitz = lipschitz_;
    double restart_test = 0.0;
    for (int halvings = 0;; ++halvings) {
      // Projected gradient step from y with the slip bias frozen: g = U(y) + s n.
      const double step = 1.0 / lipschitz;
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
      for (std::ptrdiff_t c = 0; c < n; ++c) {
        if (!problem.solvable(static_cast<std::size_t>(c))) {
          x_[c].setZero();
          continue;
        }
        const double w_n = problem.w_n[c], w_t = problem.w_t[c];
        const Eigen::Vector3d& g = uy_[c];
        const Eigen::Vector3d tau(y_[c][0] - step * (g[0] + slip_bias_[c]) / w_n,
                                  y_[c][1] - step * g[1] / w_t, y_[c][2] - step * g[2] / w_t);
        x_[c] = project_in_metric(tau, w_n, w_t, problem.mu[c], planar);
      }
      local_velocities(problem, x_, velocity, angular_velocity, ux_);
      // Curvature (x-y).W(x-y) = (x-y).(U(x)-U(y)) against L |x-y|_D^2, and the restart
      // test g(y).(x - x_old).
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
      for (std::ptrdiff_t block = 0; block < blocks; ++block) {
        double curvature = 0.0, metric = 0.0, ascent = 0.0;
        for (std::ptrdiff_t c = block * kBlock; c < std::min(n, (block + 1) * kBlock); ++c) {
          const Eigen::Vector3d d = x_[c] - y_[c];
          curvature += d.dot(ux_[c] - uy_[c]);
          metric += problem.w_n[c] * d[0] * d[0] + problem.w_t[c] * (d[1] * d[1] + d[2] * d[2]);
          const Eigen::Vector3d g(uy_[c][0] + slip_bias_[c], uy_[c][1], uy_[c][2]);
          ascent += g.dot(x_[c] - x_old_[c]);
        }
        partial_a_[3 * block] = curvature;
        partial_a_[3 * block + 1] = metric;
        partial_a_[3 * block + 2] = ascent;
      }
      const auto [curvature, metric, ascent] = add_block_sums<3>(partial_a_, blocks);
      restart_test = ascent;
      // 60 halvings: the curvature is not finite (NaN input); the residual will say so.
      if (curvature <= lipschitz * metric * (1.0 + 1e-12) || halvings == 60) break;
      lipschitz *= 2.0;  // step too long for the local curvature: halve it
    }
    const double residual = residual_and_slip();
    if (residual < best_residual) {
      best_residual = residual;
      best_sweep = report.sweeps;
      best_.assign(x_.begin(), x_.end());
    }
    if (residual < 0.9 * progress) {
      progress = residual;
      progress_sweep = report.sweeps;
    }
    // The scaled operator has a unit diagonal, so its largest eigenvalue is at least 1.
    lipschitz_ = std::max(1.0, 0.9 * lipschitz);
    if (restart_test > 0.0) {  // momentum points uphill: restart from x
      theta = 1.0;
      y_.assign(x_.begin(), x_.end());
      uy_.assign(ux_.begin(), ux_.end());
      continue;
    }
    const double next_theta = 0.5 * (-theta * theta + theta * std::sqrt(theta * theta + 4.0));
    const double beta = theta * (1.0 - theta) / (theta * theta + next_theta);
    theta = next_theta;
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
    for (std::ptrdiff_t c = 0; c < n; ++c) {
      y_[c] = x_[c] + beta * (x_[c] - x_old_[c]);
      uy_[c] = ux_[c] + beta * (ux_[c] - ux_old_[c]);  // U is affine in r
    }
  }

  r.assign(best_.begin(), best_.end());
  if (best_sweep != report.sweeps) local_velocities(problem, best_, velocity, angular_velocity, uy_);
  report.residual = best_residual;
  report.converged = best_residual <= settings_.tolerance;
  return report;
}

}  // namespace tmdem::mechanics
