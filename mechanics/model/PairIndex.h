#pragma once
// How a contact names its second body. Every contact table (candidate pairs, touching pairs,
// contact forces, the coupling's contact list and the result file's /contacts/pair) stores
// (i, j) with i a particle id and j either a particle id (j > i) or a wall, encoded as
// j = -1 - wall index, so one signed integer covers both without a separate flag.
// Read and write that encoding only through these helpers, whatever the integer width.

#include <cassert>
#include <concepts>
#include <cstddef>

namespace tmdem::mechanics {

// True when j names a wall rather than a particle.
template <std::signed_integral Index>
constexpr bool is_wall(Index j) { return j < 0; }

// Index into the wall list of a j that names a wall.
template <std::signed_integral Index>
constexpr std::size_t wall_index(Index j) {
  assert(is_wall(j));
  return static_cast<std::size_t>(-1 - j);
}

// The j that names wall number `wall`, in the table's integer type.
template <std::signed_integral Index>
constexpr Index wall_code(std::size_t wall) { return static_cast<Index>(-1 - static_cast<Index>(wall)); }

}  // namespace tmdem::mechanics
