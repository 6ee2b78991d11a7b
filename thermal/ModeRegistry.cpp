#include "thermal/ModeRegistry.h"

#include <map>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

#define TMDEM_HEAT_MODE(name) std::unique_ptr<HeatTransferMode> make_##name##_mode(const ModeSettings&);
#include "thermal/ModeList.h"
#undef TMDEM_HEAT_MODE

namespace {
using Factory = std::unique_ptr<HeatTransferMode> (*)(const ModeSettings&);
struct Entry {
  std::string_view name;
  Factory make;
};
constexpr Entry kModes[] = {
#define TMDEM_HEAT_MODE(name) {#name, &make_##name##_mode},
#include "thermal/ModeList.h"
#undef TMDEM_HEAT_MODE
};

std::map<std::string, int, std::less<>>& construction_counts() {
  static std::map<std::string, int, std::less<>> counts;
  return counts;
}
}  // namespace

std::vector<std::string_view> heat_transfer_mode_names() {
  std::vector<std::string_view> names;
  for (const auto& m : kModes) names.push_back(m.name);
  return names;
}

std::unique_ptr<HeatTransferMode> make_heat_transfer_mode(std::string_view name,
                                                          const ModeSettings& settings) {
  for (const auto& m : kModes) {
    if (m.name == name) {
      ++construction_counts()[std::string(name)];
      return m.make(settings);
    }
  }
  std::string valid;
  for (const auto& m : kModes) valid += (valid.empty() ? "" : ", ") + std::string(m.name);
  throw std::invalid_argument("unknown heat-transfer mode \"" + std::string(name) +
                              "\"; valid types are: " + valid);
}

int heat_transfer_mode_constructions(std::string_view name) {
  const auto& counts = construction_counts();
  const auto it = counts.find(name);
  return it == counts.end() ? 0 : it->second;
}

}  // namespace tmdem::thermal
