#pragma once
// A kind chosen by name (thermal.integrator, thermal.linear_solver, thermal.conductance,
// thermal.particle_resistance): the names are one array in the enum's order, written once next
// to the enum, and a name is parsed into its kind once, at the scene's edge; past it the code
// compares kinds, never strings. In the lowest room so that every room can name its kinds.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tmdem::thermal {

// The kind whose name is `name`; std::invalid_argument "unknown WHAT "NAME"; valid types are:
// a, b, c" otherwise.
template <class Kind, std::size_t N>
Kind parse_kind(std::string_view name, const std::array<std::string_view, N>& names,
                const char* what) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Kind>(i);
  std::string valid;
  for (auto n : names) valid += (valid.empty() ? "" : ", ") + std::string(n);
  throw std::invalid_argument(std::string("unknown ") + what + " \"" + std::string(name) +
                              "\"; valid types are: " + valid);
}

template <class Kind, std::size_t N>
constexpr std::string_view kind_name(Kind kind, const std::array<std::string_view, N>& names) {
  return names[static_cast<std::size_t>(kind)];
}

}  // namespace tmdem::thermal
