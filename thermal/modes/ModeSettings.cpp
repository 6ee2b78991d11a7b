#include "thermal/modes/ModeSettings.h"

namespace tmdem::thermal {

void ModeSettings::set(std::string_view mode, std::string_view key, double value) {
  values_[{std::string(mode), std::string(key)}] = value;
}

std::optional<double> ModeSettings::find(std::string_view mode, std::string_view key) const {
  const auto it = values_.find(std::pair{std::string(mode), std::string(key)});
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::vector<std::string> ModeSettings::keys_of(std::string_view mode) const {
  std::vector<std::string> keys;
  for (const auto& [mode_key, value] : values_)
    if (mode_key.first == mode) keys.push_back(mode_key.second);
  return keys;
}

}  // namespace tmdem::thermal
