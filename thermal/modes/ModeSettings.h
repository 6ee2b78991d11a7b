#pragma once
// Parameter values of the heat-transfer modes, by mode name and key ("convection",
// "coefficient" -> 25.0). A value left unset takes the default its mode declares
// (thermal/modes/ModeDescription.h); the registry resolves and checks them when it builds a mode.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tmdem::thermal {

class ModeSettings {
 public:
  void set(std::string_view mode, std::string_view key, double value);
  std::optional<double> find(std::string_view mode, std::string_view key) const;
  // The keys set for `mode`, sorted.
  std::vector<std::string> keys_of(std::string_view mode) const;

 private:
  std::map<std::pair<std::string, std::string>, double, std::less<>> values_;
};

}  // namespace tmdem::thermal
