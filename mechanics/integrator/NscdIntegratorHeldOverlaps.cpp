// NscdIntegrator::hold_initial_overlaps (NscdIntegrator.h): the overlaps a bed starts with
// that belong to its packing, held by the position step. Apart from the step so that the step's
// code stays as it is.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics {

void NscdIntegrator::hold_initial_overlaps(std::vector<std::uint8_t> holds) {
  if (holds.size() != particles_.size())
    throw std::invalid_argument("mechanics: hold_initial_overlaps needs one flag per particle (" +
                                std::to_string(particles_.size()) + "), got " + std::to_string(holds.size()));
  holds_overlap_ = std::move(holds);
}

void NscdIntegrator::take_initial_overlaps() {
  held_overlap_.assign(problem_.size(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < problem_.size(); ++k) {
    const std::int32_t i = problem_.body_i[k], j = problem_.body_j[k];
    if (!(gap_[k] < 0.0) || !holds_overlap_[i] || (!is_wall(j) && !holds_overlap_[j])) continue;
    held_overlap_[k] = -gap_[k];
    any = true;
  }
  if (!any) held_overlap_.clear();
  holds_overlap_.clear();  // taken: the first step's overlaps only
}

void NscdIntegrator::add_held_overlaps(std::vector<double>& gap_m) {
  for (std::size_t k = 0; k < gap_m.size(); ++k) {
    // Only ever less: a pair that opens gives up what it opened by, for good.
    held_overlap_[k] = std::min(held_overlap_[k], std::max(0.0, -gap_m[k]));
    gap_m[k] += held_overlap_[k];
  }
}

std::size_t NscdIntegrator::held_overlaps() const {
  return static_cast<std::size_t>(std::count_if(held_overlap_.begin(), held_overlap_.end(),
                                                [](double x) { return x > 0.0; }));
}

double NscdIntegrator::largest_held_overlap_m() const {
  double largest = 0.0;
  for (const double x : held_overlap_) largest = std::max(largest, x);
  return largest;
}

}  // namespace tmdem::mechanics
