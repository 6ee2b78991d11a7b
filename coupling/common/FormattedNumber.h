#pragma once
// A number in a printf format ("%.3g", "%.2e"), for messages and reports that show a figure to
// a reader; shortest_number (ShortestNumber.h) is for text that is read back.
#include <cstdio>
#include <string>

namespace tmdem::coupling {

inline std::string formatted_number(const char* printf_format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, printf_format, value);
  return buffer;
}

}  // namespace tmdem::coupling
