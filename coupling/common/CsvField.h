#pragma once
// A text as one CSV field (RFC 4180): in double quotes, its own quotes doubled. csv_quoted
// always quotes (a column a reader knows to be quoted); csv_field only when the text holds a
// separator, a quote or a line break.
#include <string>

namespace tmdem::coupling {

inline std::string csv_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

inline std::string csv_field(const std::string& text) {
  return text.find_first_of(",\"\r\n") == std::string::npos ? text : csv_quoted(text);
}

}  // namespace tmdem::coupling
