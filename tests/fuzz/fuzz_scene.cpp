// libFuzzer target: scene text -> load_scene_text (parse, --set overrides, validate, generate).
// Any input must either load or throw SceneError; another exception escapes and libFuzzer
// reports it as a crash, as it does a sanitizer report or a hang (-timeout).
// Leading lines "#set KEY=VALUE" (TOML comments, so the text still parses) are also passed as
// --set overrides, so the override path is fuzzed too.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  std::size_t at = 0;
  while (text.substr(at).starts_with("#set ")) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    overrides.emplace_back(text.substr(at + 5, end - at - 5));
    at = end + 1;
    if (at >= text.size()) break;
  }
  try {
    (void)tmdem::coupling::load_scene_text(text, "fuzz.toml", overrides);
  } catch (const tmdem::coupling::SceneError&) {
    // A refused scene is the expected outcome for most inputs.
  }
  return 0;
}
