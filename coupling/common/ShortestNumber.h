#pragma once
// Shortest text that reads back to the same double ("0.01", "1e-10", "0.0043"; "nan", "inf",
// "-inf"). One formatter for scene messages, TOML, XDMF and CSV output, so a number written by
// one and read by another is the same double.
#include <charconv>
#include <cmath>
#include <string>

namespace tmdem::coupling {

inline std::string shortest_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace tmdem::coupling
