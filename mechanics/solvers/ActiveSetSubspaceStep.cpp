#include "mechanics/solvers/ActiveSetSubspaceStep.h"

#include <algorithm>
#include <cmath>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/CoulombCone.h"
#include "mechanics/contact/NaturalMapResidual.h"

namespace tmdem::mechanics {
namespace {

// A contact sticks when its tangential impulse is inside the cone by more than round-off; the
// sweeps leave a sliding contact on the cone's edge (CoulombCone.h), to its last bits.
constexpr double kStickMargin = 1.0 - 1e-12;

// The slot of entry (row, col) in a compressed column-major matrix (present by construction).
std::int32_t slot_of(const Eigen::SparseMatrix<double>& matrix, int row, int col) {
  const int* inner = matrix.innerIndexPtr();
  const int* begin = inner + matrix.outerIndexPtr()[col];
  const int* end = inner + matrix.outerIndexPtr()[col + 1];
  return static_cast<std::int32_t>(std::lower_bound(begin, end, row) - inner);
}

}  // namespace

ActiveSetSubspaceStep::ActiveSetSubspaceStep(const Options& options) : options_(options) {}

bool ActiveSetSubspaceStep::classify(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                                     const std::vector<Eigen::Vector3d>& velocity) {
  const std::int32_t stick_size = problem.dimension == 2 ? 2 : 3;
  active_.clear();
  offset_.clear();
  size_.clear();
  pattern_key_.clear();
  std::int32_t unknowns = 0;
  double speed_scale = 0.0;  // m/s
  for (const auto& v : problem.free_velocity) speed_scale = std::max(speed_scale, v.norm());
  const double resting_speed = 1e-9 * speed_scale;
  for (std::size_t c = 0; c < problem.size(); ++c) {
    if (!problem.solvable(c)) continue;
    // Open contacts that are closing or resting (r = 0, u_n <= 1e-9 of the fastest free speed)
    // join with their normal component: the load the sweeps have not yet carried to them is
    // solved with the rest. "Resting" takes in contacts a gap of round-off leaves a hair open:
    // from cold, a sweep carries a column's load up only until its velocity increments fall
    // below double precision (about 42 layers per sweep pair), and the spheres above fall
    // together, their contacts neither closing nor opening.
    bool resting = false;
    if (!(r[c][0] > 0.0)) {
      if (!r[c].isZero(0.0)) continue;
      const double un = normal_velocity(problem, c, velocity);
      if (!(un <= resting_speed)) continue;
      resting = un >= -resting_speed;
    }
    const double rt = r[c].tail<2>().norm(), limit = problem.mu[c] * r[c][0];
    const bool stick = !resting && rt < options_.stick_fraction * limit;
    if (!stick && !resting && rt < kStickMargin * limit) continue;  // near the edge: left to the sweeps
    const std::int32_t size = stick ? stick_size : 1;
    active_.push_back(static_cast<std::int32_t>(c));
    offset_.push_back(unknowns);
    size_.push_back(size);
    unknowns += size;
    pattern_key_.insert(pattern_key_.end(),
                        {static_cast<std::int32_t>(c), size, problem.body_i[c], problem.body_j[c]});
  }
  offset_.push_back(unknowns);
  return !active_.empty();
}

template <class Emit>
void ActiveSetSubspaceStep::for_each_contribution(const ContactProblem& problem, Emit&& emit) const {
  const std::size_t bodies = problem.body_count();
  for (std::size_t b = 0; b < bodies; ++b) {
    const double im = problem.inverse_mass[b], ii = problem.inverse_inertia[b];
    for (std::int32_t p = body_start_[b]; p < body_start_[b + 1]; ++p) {
      const std::int32_t kp = body_entries_[p] >> 1, sp = body_entries_[p] & 1;
      // Entries of a body come in increasing active index: kq <= kp, the lower triangle.
      for (std::int32_t q = body_start_[b]; q <= p; ++q) {
        const std::int32_t kq = body_entries_[q] >> 1, sq = body_entries_[q] & 1;
        const Eigen::Matrix3d block = im * linear_[sp][kp].transpose() * linear_[sq][kq] +
                                      ii * angular_[sp][kp].transpose() * angular_[sq][kq];
        for (std::int32_t a = 0; a < size_[kp]; ++a) {
          for (std::int32_t e = 0; e < size_[kq]; ++e) {
            if (kp == kq && e > a) continue;
            emit(offset_[kp] + a, offset_[kq] + e, block(a, e));
          }
        }
      }
    }
  }
}

bool ActiveSetSubspaceStep::assemble_and_factorise(const ContactProblem& problem) {
  const std::size_t count = active_.size(), bodies = problem.body_count();
  const int unknowns = offset_[count];
  // Each side's velocity change per unit local impulse (ContactKinematics.h, contact_columns):
  // body i takes +p at -R_i n, a particle j -p at +R_j n (both turn by -R n x p), a piston j
  // -r_n n along its normal only, a fixed wall nothing (not mobile: no entries).
  for (auto* v : {&linear_[0], &linear_[1], &angular_[0], &angular_[1]}) v->resize(count);
  body_start_.assign(bodies + 1, 0);
  auto mobile = [&](std::size_t b) { return problem.inverse_mass[b] > 0.0 || problem.inverse_inertia[b] > 0.0; };
  auto body_of = [&](std::size_t c, int side) -> std::size_t {
    const std::int32_t j = problem.body_j[c];
    if (side == 0) return static_cast<std::size_t>(problem.body_i[c]);
    return is_wall(j) ? problem.wall_body(j) : static_cast<std::size_t>(j);
  };
  for (std::size_t k = 0; k < count; ++k) {
    const auto c = static_cast<std::size_t>(active_[k]);
    const ContactColumns columns = contact_columns(problem, c);
    for (int side = 0; side < 2; ++side) {
      linear_[side][k] = columns.linear[side];
      angular_[side][k] = columns.angular[side];
    }
    for (int side = 0; side < 2; ++side)
      if (mobile(body_of(c, side))) ++body_start_[body_of(c, side) + 1];
  }
  for (std::size_t b = 0; b < bodies; ++b) body_start_[b + 1] += body_start_[b];
  body_entries_.resize(static_cast<std::size_t>(body_start_[bodies]));
  // Filled in increasing active index (for_each_contribution relies on it).
  cursor_.assign(body_start_.begin(), body_start_.end() - 1);
  for (std::size_t k = 0; k < count; ++k)
    for (int side = 0; side < 2; ++side)
      if (const std::size_t b = body_of(static_cast<std::size_t>(active_[k]), side); mobile(b))
        body_entries_[cursor_[b]++] = static_cast<std::int32_t>(2 * k + side);

  const bool new_pattern = !have_pattern_ || pattern_key_ != last_key_;
  if (new_pattern) {
    triplets_.clear();
    for_each_contribution(problem, [&](int row, int col, double value) { triplets_.emplace_back(row, col, value); });
    matrix_.resize(unknowns, unknowns);
    matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
    matrix_.makeCompressed();
    value_index_.resize(triplets_.size());
    for (std::size_t t = 0; t < triplets_.size(); ++t)
      value_index_[t] = slot_of(matrix_, triplets_[t].row(), triplets_[t].col());
    diagonal_index_.resize(static_cast<std::size_t>(unknowns));
    for (int u = 0; u < unknowns; ++u) diagonal_index_[u] = slot_of(matrix_, u, u);
    factor_.analyzePattern(matrix_);
    last_key_ = pattern_key_;
    have_pattern_ = true;
    ++patterns_;
  }
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  std::size_t t = 0;
  for_each_contribution(problem, [&](int, int, double value) { values[value_index_[t++]] += value; });
  // A compliant problem's W + C: each active contact's normal unknown (its first) takes its
  // compliance (ContactProblem::compliance), which makes W_AA positive definite.
  if (problem.compliant)
    for (std::size_t k = 0; k < active_.size(); ++k)
      values[diagonal_index_[offset_[k]]] += problem.compliance[static_cast<std::size_t>(active_[k])];
  diagonal_.resize(unknowns);
  for (int u = 0; u < unknowns; ++u) {
    diagonal_[u] = values[diagonal_index_[u]];
    values[diagonal_index_[u]] += options_.proximal * diagonal_[u];
  }
  factor_.factorize(matrix_);
  ++factorisations_;
  return factor_.info() == Eigen::Success;
}

bool ActiveSetSubspaceStep::take(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                              std::vector<Eigen::Vector3d>& velocity,
                                              std::vector<Eigen::Vector3d>& angular_velocity) {
  ++tried_;
  saved_r_.assign(r.begin(), r.end());
  saved_v_.assign(velocity.begin(), velocity.end());
  saved_w_.assign(angular_velocity.begin(), angular_velocity.end());
  const double before = natural_map_residual(problem, r, velocity, angular_velocity);
  double best = before;
  const bool planar = problem.dimension == 2;
  for (int pass = 0; pass < options_.active_passes; ++pass) {
    if (!classify(problem, r, velocity)) break;
    if (!assemble_and_factorise(problem)) break;
    const std::size_t count = active_.size();
    const int unknowns = offset_[count];
    // residual = -U_A, the active components of the local velocities.
    residual_.resize(unknowns);
    pass_start_.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const auto c = static_cast<std::size_t>(active_[k]);
      Eigen::Vector3d u = local_velocity<Eigen::Vector3d>(problem, c, velocity, angular_velocity);
      if (problem.compliant) u[0] += problem.compliance[c] * r[c][0];  // U of W + C
      for (std::int32_t a = 0; a < size_[k]; ++a) residual_[offset_[k] + a] = -u[a];
      pass_start_[k] = r[c];
    }
    // Proximal point: (W + rho D) dx = -U_A(x), U_A(x) = U_A(0) + W x.
    x_.setZero(unknowns);
    const double start = residual_.norm();
    for (int iteration = 0; iteration < options_.proximal_iterations; ++iteration) {
      step_ = factor_.solve(residual_);
      x_ += step_;
      product_.noalias() = matrix_.selfadjointView<Eigen::Lower>() * step_;
      product_ -= options_.proximal * diagonal_.cwiseProduct(step_);
      residual_ -= product_;
      if (residual_.norm() <= 1e-14 * start) break;
    }
    // A projected line search: r_A = proj(r_A + alpha x) for alpha = 1, 1/2, 1/4, ..., kept at
    // the first that lowers the merit below the best so far. A contact the projection moves
    // (opens, or reaches the cone's edge) has left its status: then another pass.
    int moved = 0;
    bool improved = false;
    double alpha = 1.0;
    for (int trial = 0; trial < options_.line_search_steps; ++trial, alpha *= 0.5) {
      moved = 0;
      for (std::size_t k = 0; k < count; ++k) {
        const auto c = static_cast<std::size_t>(active_[k]);
        const double mu = problem.mu[c];
        const Eigen::Vector3d& from = pass_start_[k];
        Eigen::Vector3d next = from;
        if (size_[k] == 1) {  // sliding: r_n solved, r_t kept on the edge in its direction
          const double rn = from[0] + alpha * x_[offset_[k]];
          const double rt = from.tail<2>().norm();
          if (rn > 0.0) {
            next[0] = rn;
            if (rt > 0.0) next.tail<2>() *= mu * rn / rt;
          } else {
            next.setZero();
            if (from[0] > 0.0) ++moved;  // a loaded contact opened; a resting one stays open
          }
        } else {
          for (std::int32_t a = 0; a < size_[k]; ++a) next[a] += alpha * x_[offset_[k] + a];
          const Eigen::Vector3d projected = project_onto_coulomb_cone(next, mu);
          if (projected != next) ++moved;
          next = projected;
        }
        if (planar) next[2] = 0.0;
        const Eigen::Vector3d change = next - r[c];
        apply_impulse(problem, c, change, velocity, angular_velocity);
        r[c] = next;
      }
      const double after = natural_map_residual(problem, r, velocity, angular_velocity);
      if (after < best) {
        best = after;
        improved = true;
        break;
      }
    }
    if (!improved) {  // back to the pass's start
      for (std::size_t k = 0; k < count; ++k) {
        const auto c = static_cast<std::size_t>(active_[k]);
        const Eigen::Vector3d change = pass_start_[k] - r[c];
        apply_impulse(problem, c, change, velocity, angular_velocity);
        r[c] = pass_start_[k];
      }
      break;
    }
    if (moved == 0) break;
  }
  if (best < before) {
    ++accepted_;
    return true;
  }
  r.assign(saved_r_.begin(), saved_r_.end());
  velocity.assign(saved_v_.begin(), saved_v_.end());
  angular_velocity.assign(saved_w_.begin(), saved_w_.end());
  return false;
}

void ActiveSetSubspaceStep::start_solve() {
  tried_ = accepted_ = patterns_ = factorisations_ = 0;
  wait_ = 1;
  waited_ = 0;
}

bool ActiveSetSubspaceStep::after_pair(const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
                                       std::vector<Eigen::Vector3d>& velocity,
                                       std::vector<Eigen::Vector3d>& angular_velocity) {
  if (++waited_ < wait_) return false;
  waited_ = 0;
  const bool kept = take(problem, r, velocity, angular_velocity);
  wait_ = kept ? 1 : std::min(2 * wait_, kMaxWait);
  return kept;
}

}  // namespace tmdem::mechanics
