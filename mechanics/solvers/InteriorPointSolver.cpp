#include "mechanics/solvers/InteriorPointSolver.h"

#include "mechanics/solvers/InteriorPointFactor.h"
#include "mechanics/solvers/SerialBlas.h"
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/contact/NaturalMapResidual.h"
#include "mechanics/contact/SiconosResidual.h"
#include "mechanics/solvers/NncgSolver.h"
#include "mechanics/solvers/SecondOrderCone.h"
#include "mechanics/model/StepInterrupt.h"

namespace tmdem::mechanics {

InteriorPointSolver::InteriorPointSolver(const SolverSettings& settings)
    : InteriorPointSolver(settings, Options{}) {}

InteriorPointSolver::InteriorPointSolver(const SolverSettings& settings, const Options& options)
    : settings_(settings), options_(options), factor_(std::make_unique<Factor>()) {
  factor_->llt.cholmod().print = 0;  // a failed factorisation is retried (assemble_and_factorise)
  if (options_.polish_sweeps > 0) {
    SolverSettings polishing = settings_;
    // Within the solve's own budget (mechanics.max_iterations).
    polishing.max_iterations = std::min(options_.polish_sweeps, settings_.max_iterations);
    polishing.siconos_stop = true;
    polishing.residual_check_every = options_.polish_residual_check_every;
    polisher_ = std::make_unique<NncgSolver>(polishing);
  }
}

InteriorPointSolver::~InteriorPointSolver() = default;

void InteriorPointSolver::freeze_law(const std::vector<Eigen::Vector3d>& r) {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Columns& col = columns_[c];
    const double sigma = sigma_f_[c];
    load_[c] = std::max(r[c][0], 0.0);
    if (dim_f_[c] == 1) {
      h_f_[c] = Eigen::Vector3d(sigma * q_[c][0], 0.0, 0.0);
    } else {
      Eigen::Vector3d u = q_[c];
      for (int k = 0; k < col.count; ++k) u += col.g[k] * dv_[col.dof[k]];
      slip_[c] = mu_[c] * (planar_ ? std::abs(u[1]) : std::hypot(u[1], u[2]));
      h_f_[c] = sigma * Eigen::Vector3d((q_[c][0] + slip_[c]) / mu_[c], q_[c][1], planar_ ? 0.0 : q_[c][2]);
    }
    if (dim_r_[c] > 0) h_r_[c] = sigma_r_[c] * q_roll_[c];
  }
}

void InteriorPointSolver::next_law(const std::vector<Eigen::Vector3d>& r) {
  // The iterate stays; each cone's slack moves inside by twice its offset's change, so that the
  // infeasibility the new offsets leave can be taken out within the cone.
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    y_f_[c] = h_f_[c];
    y_r_[c] = h_r_[c];
  }
  freeze_law(r);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    s_f_[c][0] += 2.0 * (h_f_[c] - y_f_[c]).norm();
    if (dim_r_[c] > 0) s_r_[c][0] += 2.0 * (h_r_[c] - y_r_[c]).norm();
  }
}

double InteriorPointSolver::frozen_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                                            const std::vector<Eigen::Vector3d>& m,
                                            const std::vector<Eigen::Vector3d>& velocity,
                                            const std::vector<Eigen::Vector3d>& angular_velocity,
                                            double q_norm) const {
  // SiconosResidual.cpp's sum, with this convex problem's slip and rolling limits in place of
  // the iterate's own.
  double sum = 0.0;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Eigen::Vector3d u = local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity);
    const Eigen::Vector3d tau(r[c][0] - (u[0] + slip_[c]), r[c][1] - u[1], r[c][2] - u[2]);
    Eigen::Vector3d defect = r[c] - project_onto_coulomb_cone(tau, problem.mu[c]);
    if (planar_) defect[2] = 0.0;
    sum += defect.squaredNorm();
    if (dim_r_[c] == 0) continue;
    const double radius = problem.rolling_radius[c];
    const Eigen::Vector3d spin = rolling_velocity<Eigen::Vector3d>(problem, c, angular_velocity);
    const Eigen::Vector3d mc = m[c] / radius;
    Eigen::Vector3d y = mc - spin * radius;
    const double limit = rolling_limit_[c] / radius * load_[c], size = y.norm();
    if (size > limit) y *= (size > 0.0 ? limit / size : 0.0);
    sum += (mc - y).squaredNorm();
  }
  const double e = std::sqrt(sum);
  return q_norm > DBL_EPSILON ? e / q_norm : e;
}

void InteriorPointSolver::residuals() {
  rx_ = mass_.cwiseProduct(dv_);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Columns& col = columns_[c];
    Eigen::Vector3d af = Eigen::Vector3d::Zero(), ar = Eigen::Vector3d::Zero();
    for (int k = 0; k < col.count; ++k) {
      const double d = dv_[col.dof[k]];
      af += col.friction[k] * d;
      double dual = col.friction[k].dot(z_f_[c]);
      if (dim_r_[c] > 0) {
        ar += col.rolling[k] * d;
        dual += col.rolling[k].dot(z_r_[c]);
      }
      rx_[col.dof[k]] -= dual;
    }
    rz_f_[c] = s_f_[c] - h_f_[c] - af;
    if (dim_r_[c] > 0) {
      ar[0] = sigma_r_[c] * t_[c];
      rz_r_[c] = s_r_[c] - h_r_[c] - ar;
      rt_[c] = rolling_limit_[c] * std::max(load_[c], 0.0) - sigma_r_[c] * z_r_[c][0];
    }
  }
}

bool InteriorPointSolver::assemble_and_factorise() {
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  for (Eigen::Index d = 0; d < mass_.size(); ++d) values[diagonal_slot_[d]] += mass_[d];
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Columns& col = columns_[c];
    const Eigen::Matrix3d& yf = w2_f_[c];
    const bool rolls = dim_r_[c] > 0;
    if (rolls) {
      const Eigen::Matrix3d& yr = w2_r_[c];
      ktt_[c] = sigma_r_[c] * sigma_r_[c] * yr(0, 0);
      for (int k = 0; k < col.count; ++k) b_t_[c][k] = sigma_r_[c] * yr.row(0).dot(col.rolling[k]);
    }
    for (int k = 0; k < col.count; ++k) {
      const Eigen::Vector3d yk = yf * col.friction[k];
      const Eigen::Vector3d rk = rolls ? Eigen::Vector3d(w2_r_[c] * col.rolling[k]) : Eigen::Vector3d::Zero();
      for (int l = 0; l < col.count; ++l) {
        const std::int64_t at = block_slot_[(c * kMaxDofs + l) * kMaxDofs + k];
        if (at < 0) continue;
        double v = col.friction[l].dot(yk);
        if (rolls) v += col.rolling[l].dot(rk) - b_t_[c][l] * b_t_[c][k] / ktt_[c];
        values[at] += v;
      }
    }
  }
  factor_->llt.factorize(matrix_);
  for (double added = 1e-12; factor_->llt.info() != Eigen::Success && added < 1e-5; added *= 100.0) {
    for (Eigen::Index d = 0; d < mass_.size(); ++d) values[diagonal_slot_[d]] *= 1.0 + added;
    factor_->llt.factorize(matrix_);
    ++regularised_;
  }
  return factor_->llt.info() == Eigen::Success;
}

void InteriorPointSolver::direction(const std::vector<Eigen::Vector3d>& xi_f,
                                    const std::vector<Eigen::Vector3d>& xi_r) {
  rhs_ = -rx_;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Columns& col = columns_[c];
    y_f_[c] = w_f_[c] * xi_f[c] + w2_f_[c] * rz_f_[c];
    const bool rolls = dim_r_[c] > 0;
    if (rolls) {
      y_r_[c] = w_r_[c] * xi_r[c] + w2_r_[c] * rz_r_[c];
      rhs_t_[c] = -rt_[c] + sigma_r_[c] * y_r_[c][0];
    }
    for (int k = 0; k < col.count; ++k) {
      double v = col.friction[k].dot(y_f_[c]);
      if (rolls) v += col.rolling[k].dot(y_r_[c]) - b_t_[c][k] * rhs_t_[c] / ktt_[c];
      rhs_[col.dof[k]] += v;
    }
  }
  ddv_ = factor_->llt.solve(rhs_);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) continue;
    const Columns& col = columns_[c];
    Eigen::Vector3d af = Eigen::Vector3d::Zero(), ar = Eigen::Vector3d::Zero();
    double bd = 0.0;
    for (int k = 0; k < col.count; ++k) {
      const double d = ddv_[col.dof[k]];
      af += col.friction[k] * d;
      if (dim_r_[c] > 0) {
        ar += col.rolling[k] * d;
        bd += b_t_[c][k] * d;
      }
    }
    dz_f_[c] = y_f_[c] - w2_f_[c] * af;
    ds_f_[c] = af - rz_f_[c];
    if (dim_r_[c] > 0) {
      dt_[c] = (rhs_t_[c] - bd) / ktt_[c];
      ar[0] = sigma_r_[c] * dt_[c];
      dz_r_[c] = y_r_[c] - w2_r_[c] * ar;
      ds_r_[c] = ar - rz_r_[c];
    }
  }
}

void InteriorPointSolver::reactions(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                    std::vector<Eigen::Vector3d>& m) const {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (dim_f_[c] == 0) {
      r[c].setZero();
      if (rolling_) m[c].setZero();
      continue;
    }
    const double sigma = sigma_f_[c];
    const Eigen::Vector3d& z = z_f_[c];
    r[c] = dim_f_[c] == 1 ? Eigen::Vector3d(sigma * z[0], 0.0, 0.0)
                          : Eigen::Vector3d(sigma * z[0] / mu_[c], sigma * z[1], planar_ ? 0.0 : sigma * z[2]);
    if (!rolling_) continue;
    if (dim_r_[c] == 0) {
      m[c].setZero();
      continue;
    }
    const Eigen::Vector3d& zr = z_r_[c];
    Eigen::Vector3d mc = planar_ ? Eigen::Vector3d(sigma_r_[c] * zr[1] * problem.tangent2[c])
                                 : Eigen::Vector3d(sigma_r_[c] * (zr[1] * problem.tangent1[c] + zr[2] * problem.tangent2[c]));
    // Within the disk of this normal reaction (the iterate's limit is the last one's).
    const double limit = rolling_limit_[c] * std::max(r[c][0], 0.0), size = mc.norm();
    if (size > limit) mc *= size > 0.0 ? limit / size : 0.0;
    m[c] = mc;
  }
}

SolveReport InteriorPointSolver::solve_with_rolling(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                                    std::vector<Eigen::Vector3d>& m,
                                                    std::vector<Eigen::Vector3d>& velocity,
                                                    std::vector<Eigen::Vector3d>& angular_velocity) {
  SolveReport report;
  const std::size_t contacts = problem.size();
  for (std::size_t c = 0; c < contacts; ++c) {
    if (problem.solvable(c)) continue;
    r[c].setZero();
    if (problem.rolling) m[c].setZero();
  }
  problem.velocities_from_reactions(r, m, velocity, angular_velocity);
  const double q_norm = free_velocity_norm(problem);
  report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
  if (report.residual <= settings_.tolerance) {
    report.converged = true;
    return report;
  }
  if (step_interrupt_requested()) return report;  // the step is given up (StepInterrupt.h)
  // The factorisations' BLAS on one thread: the same bits for any OMP_NUM_THREADS (SerialBlas.h).
  const SerialBlas serial_blas;
  set_up(problem);
  start(problem, r, velocity, angular_velocity);
  const int limit = std::min(options_.max_iterations, settings_.max_iterations);
  int iteration = 0, inner = 0, since_gain = 0, laws_without_gain = 0;
  best_r_ = r;
  if (problem.rolling) best_m_ = m;
  double best = report.residual, frozen_mark = std::numeric_limits<double>::infinity();
  double best_at_law = best;
  for (; iteration < limit; ++iteration, ++inner) {
    // An iteration factorises the whole problem: a solve can last minutes (StepInterrupt.h).
    if (step_interrupt_requested()) break;
    residuals();
    if (inner > 0) {
      reactions(problem, r, m);
      problem.velocities_from_reactions(r, m, velocity, angular_velocity);
      report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
      if (report.residual <= settings_.tolerance) {
        report.converged = true;
        break;
      }
      if (report.residual < best) {
        best = report.residual;
        best_r_ = r;
        if (problem.rolling) best_m_ = m;
      }
      // A new law (Cadoux's fixed point) once this convex problem is solved well past the
      // law's own error, or its solve stalls.
      const double frozen = frozen_residual(problem, r, m, velocity, angular_velocity, q_norm);
      bool new_law = frozen <= options_.frozen_fraction * report.residual;
      if (frozen < 0.9 * frozen_mark) {
        frozen_mark = frozen;
        since_gain = 0;
      } else if (++since_gain >= options_.stall_iterations) {
        new_law = true;
      }
      if (new_law) {
        laws_without_gain = best < 0.9 * best_at_law ? 0 : laws_without_gain + 1;
        best_at_law = std::min(best_at_law, best);
        if (laws_without_gain >= options_.stall_laws) {
          report.stalled = true;
          break;
        }
        ++laws_;
        next_law(r);
        inner = -1;
        frozen_mark = std::numeric_limits<double>::infinity();
        since_gain = 0;
        continue;
      }
    }
    // Scalings and the duality gap.
    double gap = 0.0;
    int cones = 0;
    // One cone's scaling into the per-contact arrays; its s . z.
    auto scale = [](int dim, const Eigen::Vector3d& sc, const Eigen::Vector3d& zc, Eigen::Matrix3d& w,
                    Eigen::Matrix3d& winv, Eigen::Matrix3d& w2, Eigen::Vector3d& lambda) {
      const cone::Scaling nt = cone::nesterov_todd(dim, sc, zc);
      w = nt.w;
      winv = nt.w_inverse;
      w2 = nt.w * nt.w;
      lambda = nt.lambda;
      return sc.dot(zc);
    };
    for (std::size_t c = 0; c < contacts; ++c) {
      if (dim_f_[c] == 0) continue;
      gap += scale(dim_f_[c], s_f_[c], z_f_[c], w_f_[c], winv_f_[c], w2_f_[c], lambda_f_[c]);
      ++cones;
      if (dim_r_[c] == 0) continue;
      gap += scale(dim_r_[c], s_r_[c], z_r_[c], w_r_[c], winv_r_[c], w2_r_[c], lambda_r_[c]);
      ++cones;
    }
    if (cones == 0) break;
    if (!assemble_and_factorise()) {
      report.stalled = true;
      break;
    }
    // Predictor: xi = lambda \ (-lambda o lambda) = -lambda.
    for (std::size_t c = 0; c < contacts; ++c) {
      xi_f_[c] = -lambda_f_[c];
      xi_r_[c] = -lambda_r_[c];
    }
    direction(xi_f_, xi_r_);
    auto longest_step = [&]() {
      double alpha = std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < contacts; ++c) {
        if (dim_f_[c] == 0) continue;
        alpha = std::min({alpha, cone::step_to_boundary(dim_f_[c], s_f_[c], ds_f_[c]),
                          cone::step_to_boundary(dim_f_[c], z_f_[c], dz_f_[c])});
        if (dim_r_[c] == 0) continue;
        alpha = std::min({alpha, cone::step_to_boundary(dim_r_[c], s_r_[c], ds_r_[c]),
                          cone::step_to_boundary(dim_r_[c], z_r_[c], dz_r_[c])});
      }
      return alpha;
    };
    const double alpha_affine = std::min(1.0, longest_step());
    double gap_affine = 0.0;
    for (std::size_t c = 0; c < contacts; ++c) {
      if (dim_f_[c] == 0) continue;
      gap_affine += (s_f_[c] + alpha_affine * ds_f_[c]).dot(z_f_[c] + alpha_affine * dz_f_[c]);
      if (dim_r_[c] > 0) gap_affine += (s_r_[c] + alpha_affine * ds_r_[c]).dot(z_r_[c] + alpha_affine * dz_r_[c]);
    }
    const double centring = std::pow(std::clamp(gap_affine / gap, 0.0, 1.0), 3);
    const double target = centring * gap / cones;
    // Corrector: lambda o xi = -lambda o lambda - (W ds_a) o (W^-1 dz_a) + target e.
    auto corrected = [&](int dim, const Eigen::Vector3d& lambda, const Eigen::Matrix3d& w, const Eigen::Matrix3d& winv,
                         const Eigen::Vector3d& ds, const Eigen::Vector3d& dz) {
      Eigen::Vector3d rhs = -cone::jordan_product(dim, lambda, lambda) -
                            cone::jordan_product(dim, w * ds, winv * dz);
      rhs[0] += target;
      return cone::jordan_divide(dim, lambda, rhs);
    };
    for (std::size_t c = 0; c < contacts; ++c) {
      if (dim_f_[c] == 0) continue;
      xi_f_[c] = corrected(dim_f_[c], lambda_f_[c], w_f_[c], winv_f_[c], ds_f_[c], dz_f_[c]);
      if (dim_r_[c] > 0) xi_r_[c] = corrected(dim_r_[c], lambda_r_[c], w_r_[c], winv_r_[c], ds_r_[c], dz_r_[c]);
    }
    direction(xi_f_, xi_r_);
    const double alpha = std::min(1.0, options_.step_fraction * longest_step());
    dv_ += alpha * ddv_;
    for (std::size_t c = 0; c < contacts; ++c) {
      if (dim_f_[c] == 0) continue;
      s_f_[c] += alpha * ds_f_[c];
      z_f_[c] += alpha * dz_f_[c];
      if (dim_r_[c] == 0) continue;
      t_[c] += alpha * dt_[c];
      s_r_[c] += alpha * ds_r_[c];
      z_r_[c] += alpha * dz_r_[c];
    }
  }
  iterations_total_ += iteration;
  int polished = 0;
  const bool crossed = report.converged && options_.crossover;
  if (crossed) {
    // An interior iterate keeps every reaction strictly inside its cone, open candidates' too,
    // and Siconos' residual, relative to ||q|| (which their gaps / h inflate) and in N s for
    // light bodies, does not see what those leftovers do: on piston_cylinder's landing (3,471
    // candidates, ||q|| = 65 m/s against 0.4 for the loaded ones) "ipm" stopped at 4.2e-5 with
    // 3e-6 N s on each open candidate, and spheres left at 8 m/s (the local-rho residual of
    // NaturalMapResidual.h: 0.24). The crossover: every reaction that its contact's exact local
    // solve, the others frozen, sets to 0 is set to 0 (the open candidates), and the loaded ones
    // keep the interior point's accuracy; the polishing sweeps follow only if Siconos' residual
    // is then above the tolerance. (Sweeps alone, run to their own stop test, cost 40-1,500 on
    // the lattice piles of bench_solvers where the interior point took 4-5 iterations.)
    bool zeroed = false;
    for (std::size_t c = 0; c < contacts; ++c) {
      if (!problem.solvable(c) || r[c].isZero()) continue;
      const Eigen::Vector3d u = local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity);
      if (!local_law_solution(problem, c, r[c], u).isZero()) continue;
      r[c].setZero();
      if (problem.rolling) m[c].setZero();
      zeroed = true;
    }
    if (zeroed) problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    if (report.residual > settings_.tolerance && polisher_) {
      polished += polisher_->solve_with_rolling(problem, r, m, velocity, angular_velocity).sweeps;
      report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    }
    polish_total_ += polished;
    report.converged = report.residual <= settings_.tolerance;
  }
  if (!report.converged && !crossed) {
    // The best iterate, polished by Gauss-Seidel sweeps.
    reactions(problem, r, m);
    problem.velocities_from_reactions(r, m, velocity, angular_velocity);
    report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    if (report.residual > best) {
      r = best_r_;
      if (problem.rolling) m = best_m_;
      problem.velocities_from_reactions(r, m, velocity, angular_velocity);
      report.residual = best;
    }
    if (polisher_ && report.residual > settings_.tolerance) {
      const SolveReport polish = polisher_->solve_with_rolling(problem, r, m, velocity, angular_velocity);
      polished = polish.sweeps;
      polish_total_ += polished;
      report.residual = siconos_residual(problem, r, m, velocity, angular_velocity, q_norm);
    }
    report.converged = report.residual <= settings_.tolerance;
    report.stalled = report.stalled && !report.converged;
  }
  report.sweeps = iteration + polished;
  return report;
}

}  // namespace tmdem::mechanics
