#include "mechanics/solvers/ContactColouring.h"

#include <algorithm>
#include <bit>

namespace tmdem::mechanics {

bool ContactColouring::update(const ContactProblem& problem) {
  if (!start_.empty() && problem.body_i == body_i_ && problem.body_j == body_j_) return false;
  body_i_ = problem.body_i;
  body_j_ = problem.body_j;
  // Colour sets of 64 colours per word; a denser graph retries with more words.
  for (std::size_t words = 1; !colour(problem, words); words *= 2) {
  }
  ++recolourings_;
  return true;
}

bool ContactColouring::colour(const ContactProblem& problem, std::size_t words) {
  const std::size_t count = problem.size(), bodies = problem.body_count();
  used_.assign(bodies * words, 0);
  colour_.resize(count);
  std::size_t colours = 0;
  for (std::size_t c = 0; c < count; ++c) {
    const std::size_t i = static_cast<std::size_t>(problem.body_i[c]);
    // A fixed wall is only read (its velocity stays 0); a piston's velocity is written.
    const std::int32_t body_j = problem.body_j[c];
    const std::size_t j = is_wall(body_j) ? problem.wall_body(body_j) : static_cast<std::size_t>(body_j);
    const bool particle_j = !is_wall(body_j) || problem.inverse_mass[j] > 0.0;
    std::size_t k = words * 64;
    for (std::size_t w = 0; w < words; ++w) {
      const std::uint64_t taken = used_[i * words + w] | (particle_j ? used_[j * words + w] : 0);
      if (taken != ~std::uint64_t{0}) {
        k = w * 64 + static_cast<std::size_t>(std::countr_one(taken));
        break;
      }
    }
    if (k == words * 64) return false;
    const std::uint64_t bit = std::uint64_t{1} << (k % 64);
    used_[i * words + k / 64] |= bit;
    if (particle_j) used_[j * words + k / 64] |= bit;
    colour_[c] = static_cast<std::int32_t>(k);
    colours = std::max(colours, k + 1);
  }
  // Counting sort by colour; contacts keep increasing index order inside a colour.
  start_.assign(colours + 1, 0);
  for (std::size_t c = 0; c < count; ++c) ++start_[colour_[c] + 1];
  for (std::size_t k = 0; k < colours; ++k) start_[k + 1] += start_[k];
  order_.resize(count);
  cursor_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t c = 0; c < count; ++c) order_[cursor_[colour_[c]]++] = static_cast<std::int32_t>(c);
  return true;
}

}  // namespace tmdem::mechanics
