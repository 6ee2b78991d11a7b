#include "mechanics/solvers/BlockGaussSeidelSolver.h"

#include <algorithm>

#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {

BlockGaussSeidelSolver::BlockGaussSeidelSolver(const SolverSettings& settings, double mass_ratio)
    : settings_(settings), mass_ratio_(mass_ratio) {}

void BlockGaussSeidelSolver::build_blocks(const ContactProblem& problem) {
  const std::size_t count = problem.size();
  const std::size_t bodies = problem.body_count();
  auto mass = [&](std::size_t b) { return problem.inverse_mass[b] > 0.0 ? 1.0 / problem.inverse_mass[b] : 0.0; };
  heaviest_.assign(bodies, 0.0);
  for (std::size_t c = 0; c < count; ++c) {
    if (!problem.solvable(c) || is_wall(problem.body_j[c])) continue;
    const std::size_t i = problem.body_i[c], j = problem.body_j[c];
    heaviest_[i] = std::max(heaviest_[i], mass(j));
    heaviest_[j] = std::max(heaviest_[j], mass(i));
  }
  auto is_light = [&](std::size_t b) {
    return problem.inverse_mass[b] > 0.0 && heaviest_[b] * problem.inverse_mass[b] >= mass_ratio_;
  };
  // Each contact goes to the block of its lighter light body (ties: body_i); block ids in the
  // order of the bodies' first contacts. 
  owner_.assign(count, -1);
  std::vector<std::int32_t>& block_of_body = scratch_;
  block_of_body.assign(bodies, -1);
  block_body_.clear();
  for (std::size_t c = 0; c < count; ++c) {
    if (!problem.solvable(c)) continue;
    const std::size_t i = problem.body_i[c];
    const bool wall = is_wall(problem.body_j[c]);
    const std::size_t j = wall ? i : static_cast<std::size_t>(problem.body_j[c]);
    std::size_t body = bodies;
    if (is_light(i) && (wall || !is_light(j) || problem.inverse_mass[i] >= problem.inverse_mass[j])) {
      body = i;
    } else if (!wall && is_light(j)) {
      body = j;
    }
    if (body == bodies) continue;
    if (block_of_body[body] < 0) {
      block_of_body[body] = static_cast<std::int32_t>(block_body_.size());
      block_body_.push_back(static_cast<std::int32_t>(body));
    }
    owner_[c] = block_of_body[body];
  }
  // Group the contacts by block (counting sort keeps index order within a block).
  const std::size_t blocks = block_body_.size();
  block_start_.assign(blocks + 1, 0);
  for (std::size_t c = 0; c < count; ++c) {
    if (owner_[c] >= 0) ++block_start_[owner_[c] + 1];
  }
  for (std::size_t b = 0; b < blocks; ++b) block_start_[b + 1] += block_start_[b];
  block_contacts_.resize(block_start_[blocks]);
  std::vector<std::int32_t>& fill = scratch_;
  fill.assign(block_start_.begin(), block_start_.end() - 1);
  for (std::size_t c = 0; c < count; ++c) {
    if (owner_[c] >= 0) block_contacts_[fill[owner_[c]]++] = static_cast<std::int32_t>(c);
  }
  quiet_.assign(blocks, 0);
}

// The sweep's block visits (GaussSeidelSweep.h, body_block order).
struct BlockGaussSeidelSolver::SweepHooks : GaussSeidelSweepHooks {
  BlockGaussSeidelSolver& solver;

  template <class Single>
  void visit_block(const GaussSeidelSweepState& state, std::size_t b, bool forward,
                   ContactUpdate& sums, Single&& single) {
    const ContactProblem& problem = state.problem;
    const std::int32_t* contacts = solver.block_contacts_.data() + solver.block_start_[b];
    const int size = solver.block_start_[b + 1] - solver.block_start_[b];
    auto singles = [&] {
      for (int k = 0; k < size; ++k) single(static_cast<std::size_t>(contacts[forward ? k : size - 1 - k]));
    };
    const double tolerance = solver.settings_.tolerance;
    if (solver.quiet_[b]) {
      // Converged to the tolerance at its last block visit: single visits, back to the block
      // as soon as they move it more than the tolerance.
      const ContactUpdate before = sums;
      singles();
      solver.quiet_[b] = sums.change - before.change <= tolerance * (sums.total - before.total);
      return;
    }
    ++solver.block_visits_;
    const BodyContactBlock::Result solved = solver.block_.solve(
        problem, static_cast<std::size_t>(solver.block_body_[b]), contacts, size, state.r, state.velocity,
        state.angular_velocity);
    if (!solved.solved) {
      ++solver.block_fallbacks_;
      singles();
      return;
    }
    sums.change += solved.update.change;
    sums.total += solved.update.total;
    solver.quiet_[b] = solved.update.change <= tolerance * solved.update.total;
    if (!problem.rolling) return;
    for (int k = 0; k < size; ++k) {
      const auto ck = static_cast<std::size_t>(contacts[k]);
      const ContactUpdate roll =
          gauss_seidel_rolling_update(problem, ck, state.r[ck][0], state.m[ck], state.angular_velocity);
      sums.change += roll.change;
      sums.total += roll.total;
    }
  }
};

SolveReport BlockGaussSeidelSolver::solve_with_rolling(const ContactProblem& problem,
                                                       std::vector<Eigen::Vector3d>& r,
                                                       std::vector<Eigen::Vector3d>& m,
                                                       std::vector<Eigen::Vector3d>& velocity,
                                                       std::vector<Eigen::Vector3d>& angular_velocity) {
  build_blocks(problem);
  block_visits_ = 0;
  block_fallbacks_ = 0;
  SweepHooks hooks{{}, *this};
  GaussSeidelSweep::Options options;
  options.full_sweep_every = 1;
  options.stall_sweeps = settings_.stall_sweeps;
  options.block_of = &owner_;
  options.block_count = block_body_.size();
  return sweep_.solve<GaussSeidelSweep::Order::body_block>(settings_, options,
                                                          {problem, r, m, velocity, angular_velocity}, hooks);
}

}  // namespace tmdem::mechanics
