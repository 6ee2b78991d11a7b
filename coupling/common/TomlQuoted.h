#pragma once
// A text as a TOML basic string ("...", backslash, quote and control characters escaped): how
// `tmdem run -o FILE` and the Python module's run(output=FILE) hand the file to the scene's
// output.file as a --set value, so that the result's resolved scene names the file written.
#include <cstdio>
#include <string>

namespace tmdem::coupling {

inline std::string toml_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += code;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace tmdem::coupling
