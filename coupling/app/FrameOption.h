#pragma once
// The --frame option of the commands that read one frame of a result (export, render):
// "last" or a frame number, negative counting from the end (ResultFrameReader.h).
#include <charconv>
#include <cstdint>
#include <optional>
#include <string>

namespace tmdem::coupling {

// -1 for "last"; nothing when the text is neither "last" nor a whole number.
inline std::optional<std::int64_t> parse_frame_option(const std::string& text) {
  if (text == "last") return -1;
  std::int64_t frame = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), frame);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return frame;
}

}  // namespace tmdem::coupling
