#include "mechanics/solvers/ColouredGaussSeidelSolver.h"

#include <algorithm>

#include "mechanics/solvers/FixedBlockSums.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"

namespace tmdem::mechanics {

ColouredGaussSeidelSolver::ColouredGaussSeidelSolver(const SolverSettings& settings,
                                                     std::ptrdiff_t parallel_from)
    : settings_(settings), parallel_from_(parallel_from) {}

SolveReport ColouredGaussSeidelSolver::solve_with_rolling(
    const ContactProblem& problem, std::vector<Eigen::Vector3d>& r,
    std::vector<Eigen::Vector3d>& m, std::vector<Eigen::Vector3d>& velocity,
    std::vector<Eigen::Vector3d>& angular_velocity) {
  colouring_.update(problem);
  const auto count = static_cast<std::ptrdiff_t>(problem.size());
  const auto colours = static_cast<std::ptrdiff_t>(colouring_.colour_count());
  const std::ptrdiff_t blocks = sum_block_count(count);
  const auto& order = colouring_.order();
  const auto& start = colouring_.start();
  const bool parallel = count >= parallel_from_;
  // The problem in colour order: contact p of ordered_ is contact order[p] of problem.
  ordered_.dimension = problem.dimension;
  ordered_.particle_count = problem.particle_count;
  ordered_.inverse_mass.assign(problem.inverse_mass.begin(), problem.inverse_mass.end());
  ordered_.inverse_inertia.assign(problem.inverse_inertia.begin(), problem.inverse_inertia.end());
  ordered_.free_velocity.assign(problem.free_velocity.begin(), problem.free_velocity.end());
  ordered_.free_angular_velocity.assign(problem.free_angular_velocity.begin(),
                                        problem.free_angular_velocity.end());
  ordered_.rolling = problem.rolling;
  ordered_.resize_contacts(static_cast<std::size_t>(count));
  ordered_r_.resize(static_cast<std::size_t>(count));
  if (problem.rolling) ordered_m_.resize(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    const auto c = static_cast<std::size_t>(order[p]);
    ordered_.copy_contact(static_cast<std::size_t>(p), problem, c);
    ordered_r_[p] = r[c];
    if (problem.rolling) ordered_m_[p] = m[c];
  }
  ordered_.velocities_from_reactions(ordered_r_, ordered_m_, velocity, angular_velocity);
  // Per visit slot (contact p in a full sweep, active()[q] in a partial one): this sweep's
  // change and total, summed in fixed blocks of slots.
  change_.resize(static_cast<std::size_t>(count));
  total_.resize(static_cast<std::size_t>(count));
  block_sums_.resize(static_cast<std::size_t>(2 * blocks));
  const double relaxation = settings_.relaxation;
  SolveReport report;
  GaussSeidelStopTest stop(settings_.tolerance, settings_.stall_sweeps);
  active_.start(static_cast<std::size_t>(count), settings_.full_sweep_every, settings_.max_iterations);
  while (report.sweeps < settings_.max_iterations) {
    ++report.sweeps;
    const bool forward = report.sweeps % 2 == 1;
    // Full sweeps visit every contact of each colour and mark the passive ones; partial
    // sweeps the colour's active contacts only (ActiveContactSet.h).
    const bool full = active_.full(report.sweeps);
    const bool mark = full && active_.partial_sweeps();  // else nothing reads the marks
    const std::vector<std::int32_t>& active = active_.active();
    const std::vector<std::int32_t>& slot_start = full ? start : active_.active_start();
    const std::ptrdiff_t slots = slot_start[static_cast<std::size_t>(colours)];
    const std::ptrdiff_t slot_blocks = sum_block_count(slots);
#pragma omp parallel if (parallel)
    {
      for (std::ptrdiff_t visit = 0; visit < colours; ++visit) {
        const std::ptrdiff_t k = forward ? visit : colours - 1 - visit;
#pragma omp for schedule(static)
        for (std::ptrdiff_t q = slot_start[k]; q < slot_start[k + 1]; ++q) {
          const auto c = static_cast<std::size_t>(full ? q : active[q]);
          ContactUpdate u;
          if (ordered_.solvable(c)) {
            u = gauss_seidel_visit(ordered_, c, relaxation, ordered_r_[c], ordered_m_, velocity,
                                   angular_velocity);
            if (mark) active_.mark_visited(c, u.total);
          } else if (mark) {
            active_.mark_unsolvable(c);
          }
          change_[q] = u.change;
          total_[q] = u.total;
        }
      }
#pragma omp for schedule(static)
      for (std::ptrdiff_t block = 0; block < slot_blocks; ++block) {
        double change = 0.0, total = 0.0;
        for (std::ptrdiff_t q = block * kSumBlock; q < std::min(slots, (block + 1) * kSumBlock); ++q) {
          change += change_[q];
          total += total_[q];
        }
        block_sums_[2 * block] = change;
        block_sums_[2 * block + 1] = total;
      }
    }
    const auto [change, total] = add_block_sums<2>(block_sums_, slot_blocks);
    if (stop.after_sweep(change, total, report, full)) break;
    if (mark) active_.collect(start);
    active_.after_sweep(full, stop.met());
  }
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t p = 0; p < count; ++p) {
    r[static_cast<std::size_t>(order[p])] = ordered_r_[p];
    if (problem.rolling) m[static_cast<std::size_t>(order[p])] = ordered_m_[p];
  }
  return report;
}

}  // namespace tmdem::mechanics
