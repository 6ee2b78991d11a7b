#include "mechanics/solvers/ApgdSolver.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "mechanics/contact/CoulombCone.h"
#include "mechanics/solvers/FixedBlockSums.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/RollingCone.h"
#include "mechanics/model/StepInterrupt.h"

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

// Projection of (tau, tau_m) onto the Coulomb and rolling cones of contact c together, in
// the metric diag(w_n, w_t, w_t, w_r I): the Euclidean projection of the scaled point onto
// the scaled cones mu' = mu sqrt(w_t / w_n), mu_r' = mu_r R_eff sqrt(w_r / w_n) (RollingCone.h).
// tau_m is first put back on the plane perpendicular to n (z only in 2D).
void project_with_rolling(const ContactProblem& problem, std::size_t c, const Eigen::Vector3d& tau,
                          Eigen::Vector3d tau_m, Eigen::Vector3d& r, Eigen::Vector3d& m) {
  const double w_n = problem.w_n[c], w_t = problem.w_t[c], w_r = problem.w_r[c];
  const bool planar = problem.dimension == 2;
  if (!(w_r > 0.0)) {  // bodies that cannot turn: no rolling impulse
    r = project_in_metric(tau, w_n, w_t, problem.mu[c], planar);
    m.setZero();
    return;
  }
  const Eigen::Vector3d& n = problem.normal[c];
  tau_m -= tau_m.dot(n) * n;
  if (planar) tau_m.x() = tau_m.y() = 0.0;
  const double sn = std::sqrt(w_n), st = std::sqrt(w_t), sr = std::sqrt(w_r);
  const TwoConeProjection p = project_onto_coulomb_and_rolling_cones(
      sn * tau[0], st * std::hypot(tau[1], planar ? 0.0 : tau[2]), problem.mu[c] * st / sn,
      sr * tau_m.norm(), problem.rolling_limit[c] * sr / sn);
  r = Eigen::Vector3d(p.normal / sn, p.tangential_factor * tau[1],
                      planar ? 0.0 : p.tangential_factor * tau[2]);
  m = p.rolling_factor * tau_m;
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

ApgdSolver::ApgdSolver(const SolverSettings& settings)
    : settings_(settings), parallel_from_(settings.parallel_from) {}

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
                                  const std::vector<Eigen::Vector3d>& m,
                                  std::vector<Eigen::Vector3d>& velocity,
                                  std::vector<Eigen::Vector3d>& angular_velocity,
                                  std::vector<Eigen::Vector3d>& u, std::vector<Eigen::Vector3d>& spin) {
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  const auto bodies = static_cast<std::ptrdiff_t>(problem.body_count());
  const auto particles = static_cast<std::ptrdiff_t>(problem.particle_count);
  const bool rolling = problem.rolling;
#pragma omp parallel if (count >= parallel_from_)
  {
#pragma omp for schedule(static)
    for (std::ptrdiff_t c = 0; c < count; ++c) {
      impulse_[c] = body_impulse(problem, static_cast<std::size_t>(c), x[c]);
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t b = 0; b < bodies; ++b) {
      Eigen::Vector3d v = problem.free_velocity[b], w = problem.free_angular_velocity[b];
      const double inverse_mass = problem.inverse_mass[b], inverse_inertia = problem.inverse_inertia[b];
      for (std::int32_t k = body_start_[b]; k < body_start_[b + 1]; ++k) {
        const std::int32_t e = body_contact_[k];
        if (e >= 0) {  // body i
          take_impulse_as_i(impulse_[e], inverse_mass, inverse_inertia, problem.lever_i[e], v, w);
          if (rolling) take_rolling_impulse_as_i(m[e], inverse_inertia, w);
        } else if (b < particles) {  // body j, a particle
          const std::int32_t c = -1 - e;
          take_impulse_as_j(impulse_[c], inverse_mass, inverse_inertia, problem.lever_j[c], v, w);
          if (rolling) take_rolling_impulse_as_j(m[c], inverse_inertia, w);
        } else {  // body j, a piston
          const std::int32_t c = -1 - e;
          take_impulse_as_piston(x[c][0], problem.normal[c], inverse_mass, v);
        }
      }
      velocity[b] = v;
      angular_velocity[b] = w;
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t c = 0; c < count; ++c) {
      const auto cc = static_cast<std::size_t>(c);
      u[c] = local_velocity<Eigen::Vector3d>(problem, cc, velocity, angular_velocity);
      if (rolling) spin[c] = rolling_velocity<Eigen::Vector3d>(problem, cc, angular_velocity);
    }
  }
}

SolveReport ApgdSolver::solve_with_rolling(const ContactProblem& problem,
                                           std::vector<Eigen::Vector3d>& r,
                                           std::vector<Eigen::Vector3d>& m,
                                           std::vector<Eigen::Vector3d>& velocity,
                                           std::vector<Eigen::Vector3d>& angular_velocity) {
  const std::size_t count = problem.size();
  const auto n = static_cast<std::ptrdiff_t>(count);
  const bool planar = problem.dimension == 2;
  const bool rolling = problem.rolling;
  const std::ptrdiff_t blocks = sum_block_count(n);
  for (auto* v : {&x_, &x_old_, &y_, &ux_, &ux_old_, &uy_, &best_}) {
    v->resize(count);
  }
  impulse_.resize(count);
  if (rolling) {
    for (auto* v : {&mx_, &mx_old_, &my_, &sx_, &sx_old_, &sy_, &mbest_}) v->resize(count);
  }
  slip_bias_.resize(count);
  partial_a_.resize(static_cast<std::size_t>(3 * blocks));
  partial_b_.resize(static_cast<std::size_t>(2 * blocks));
  velocity.resize(problem.body_count());
  angular_velocity.resize(problem.body_count());
  build_body_lists(problem);

  for (std::size_t c = 0; c < count; ++c) {
    x_[c] = problem.solvable(c) ? r[c] : Eigen::Vector3d::Zero();
    if (rolling) mx_[c] = problem.solvable(c) && problem.w_r[c] > 0.0 ? m[c] : Eigen::Vector3d::Zero();
  }
  local_velocities(problem, x_, mx_, velocity, angular_velocity, ux_, sx_);

  // Residual of x_ (from ux_, sx_) and the slip bias s = mu |u_t| (+ mu_r R_eff |w_roll|) it
  // gives, in one pass.
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
        if (rolling && problem.w_r[c] > 0.0) {
          slip_bias_[c] += problem.rolling_limit[c] * sx_[c].norm();
          const Eigen::Vector3d next_m = local_rolling_solution(problem, cc, next[0], mx_[c], sx_[c]);
          const double scale = 1.0 / problem.rolling_radius[c];
          defect += (next_m - mx_[c]).norm() * scale;
          total += next_m.norm() * scale;
        }
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
  if (rolling) {
    mbest_.assign(mx_.begin(), mx_.end());
    my_.assign(mx_.begin(), mx_.end());
    sy_.assign(sx_.begin(), sx_.end());
  }
  double theta = 1.0;
  // Stall watch, as nlgs: the sweep at which the best residual last fell by 10%.
  double progress = best_residual;
  int progress_sweep = 0;
  while (best_residual > settings_.tolerance && report.sweeps < settings_.max_iterations) {
    if (step_interrupt_requested()) break;  // the step is given up (StepInterrupt.h)
    if (report.sweeps - progress_sweep >= settings_.stall_sweeps) {
      report.stalled = true;
      break;
    }
    ++report.sweeps;
    std::swap(x_, x_old_);
    std::swap(ux_, ux_old_);
    if (rolling) {
      std::swap(mx_, mx_old_);
      std::swap(sx_, sx_old_);
    }
    double lipschitz = lipschitz_;
    double restart_test = 0.0;
    for (int halvings = 0;; ++halvings) {
      // Projected gradient step from y with the slip bias frozen: g = U(y) + s n (and the
      // rolling velocity for m).
      const double step = 1.0 / lipschitz;
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
      for (std::ptrdiff_t c = 0; c < n; ++c) {
        const auto cc = static_cast<std::size_t>(c);
        if (!problem.solvable(cc)) {
          x_[c].setZero();
          if (rolling) mx_[c].setZero();
          continue;
        }
        const double w_n = problem.w_n[c], w_t = problem.w_t[c];
        const Eigen::Vector3d& g = uy_[c];
        const Eigen::Vector3d tau(y_[c][0] - step * (g[0] + slip_bias_[c]) / w_n,
                                  y_[c][1] - step * g[1] / w_t, y_[c][2] - step * g[2] / w_t);
        if (!rolling) {
          x_[c] = project_in_metric(tau, w_n, w_t, problem.mu[c], planar);
          continue;
        }
        const double w_r = problem.w_r[c];
        const Eigen::Vector3d tau_m =
            w_r > 0.0 ? Eigen::Vector3d(my_[c] - (step / w_r) * sy_[c]) : Eigen::Vector3d::Zero();
        project_with_rolling(problem, cc, tau, tau_m, x_[c], mx_[c]);
      }
      local_velocities(problem, x_, mx_, velocity, angular_velocity, ux_, sx_);
      // Curvature (x-y).W(x-y) = (x-y).(U(x)-U(y)) against L |x-y|_D^2, and the restart
      // test g(y).(x - x_old); the rolling parts add theirs.
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
      for (std::ptrdiff_t block = 0; block < blocks; ++block) {
        double curvature = 0.0, metric = 0.0, ascent = 0.0;
        for (std::ptrdiff_t c = block * kBlock; c < std::min(n, (block + 1) * kBlock); ++c) {
          const Eigen::Vector3d d = x_[c] - y_[c];
          curvature += d.dot(ux_[c] - uy_[c]);
          metric += problem.w_n[c] * d[0] * d[0] + problem.w_t[c] * (d[1] * d[1] + d[2] * d[2]);
          const Eigen::Vector3d g(uy_[c][0] + slip_bias_[c], uy_[c][1], uy_[c][2]);
          ascent += g.dot(x_[c] - x_old_[c]);
          if (rolling) {
            const Eigen::Vector3d dm = mx_[c] - my_[c];
            curvature += dm.dot(sx_[c] - sy_[c]);
            metric += problem.w_r[c] * dm.squaredNorm();
            ascent += sy_[c].dot(mx_[c] - mx_old_[c]);
          }
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
      if (rolling) mbest_.assign(mx_.begin(), mx_.end());
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
      if (rolling) {
        my_.assign(mx_.begin(), mx_.end());
        sy_.assign(sx_.begin(), sx_.end());
      }
      continue;
    }
    const double next_theta = 0.5 * (-theta * theta + theta * std::sqrt(theta * theta + 4.0));
    const double beta = theta * (1.0 - theta) / (theta * theta + next_theta);
    theta = next_theta;
#pragma omp parallel for schedule(static) if (n >= parallel_from_)
    for (std::ptrdiff_t c = 0; c < n; ++c) {
      y_[c] = x_[c] + beta * (x_[c] - x_old_[c]);
      uy_[c] = ux_[c] + beta * (ux_[c] - ux_old_[c]);  // U is affine in (r, m)
      if (rolling) {
        my_[c] = mx_[c] + beta * (mx_[c] - mx_old_[c]);
        sy_[c] = sx_[c] + beta * (sx_[c] - sx_old_[c]);
      }
    }
  }

  r.assign(best_.begin(), best_.end());
  if (rolling) m.assign(mbest_.begin(), mbest_.end());
  if (best_sweep != report.sweeps)
    local_velocities(problem, best_, mbest_, velocity, angular_velocity, uy_, sy_);
  report.residual = best_residual;
  report.converged = best_residual <= settings_.tolerance;
  return report;
}

}  // namespace tmdem::mechanics
