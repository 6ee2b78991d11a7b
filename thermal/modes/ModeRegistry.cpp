#include "thermal/modes/ModeRegistry.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace tmdem::thermal {

#define TMDEM_HEAT_MODE(name) const ModeDescription& name##_mode();
#include "thermal/modes/ModeList.h"
#undef TMDEM_HEAT_MODE

namespace {

struct Registry {
  std::vector<const ModeDescription*> modes;
  std::uint64_t version = 0;
  std::map<std::string, int, std::less<>> constructions;
};

std::string valid_names(const std::vector<const ModeDescription*>& modes) {
  std::string valid;
  for (const auto* m : modes) valid += (valid.empty() ? "" : ", ") + std::string(m->name);
  return valid;
}

void add(Registry& registry, const ModeDescription& mode) {
  if (mode.name.empty() || mode.make == nullptr)
    throw std::invalid_argument("a heat-transfer mode needs a name and a factory");
  for (const auto* other : registry.modes) {
    if (other->name == mode.name)
      throw std::invalid_argument("heat-transfer mode \"" + std::string(mode.name) +
                                  "\" is registered twice");
    if (!mode.effect.empty() && other->effect == mode.effect &&
        other->effect_default != mode.effect_default)
      throw std::invalid_argument("effects." + std::string(mode.effect) + ": modes " +
                                  std::string(other->name) + " and " + std::string(mode.name) +
                                  " declare different defaults");
  }
  registry.modes.push_back(&mode);
  ++registry.version;
}

Registry& registry() {
  static Registry r = [] {
    Registry built_in;
#define TMDEM_HEAT_MODE(name) add(built_in, name##_mode());
#include "thermal/modes/ModeList.h"
#undef TMDEM_HEAT_MODE
    return built_in;
  }();
  return r;
}

}  // namespace

const std::vector<const ModeDescription*>& heat_transfer_modes() { return registry().modes; }

const ModeDescription* find_heat_transfer_mode(std::string_view name) {
  for (const auto* m : registry().modes)
    if (m->name == name) return m;
  return nullptr;
}

std::vector<std::string_view> heat_transfer_mode_names() {
  std::vector<std::string_view> names;
  for (const auto* m : registry().modes) names.push_back(m->name);
  return names;
}

void register_heat_transfer_mode(const ModeDescription& mode) { add(registry(), mode); }

std::uint64_t heat_transfer_registry_version() { return registry().version; }

std::vector<EffectSwitch> heat_transfer_effects() {
  std::vector<EffectSwitch> effects;
  for (const auto* m : registry().modes) {
    if (m->effect.empty()) continue;
    bool seen = false;
    for (const auto& e : effects) seen = seen || e.key == m->effect;
    if (!seen) effects.push_back({m->effect, m->effect_default, m->effect_description});
  }
  return effects;
}

ModeParameters resolve_mode_parameters(const ModeDescription& mode, const ModeSettings& settings) {
  const std::string prefix = std::string(mode.name) + ".";
  for (const auto& key : settings.keys_of(mode.name)) {
    bool declared = false;
    for (const auto& p : mode.parameters) declared = declared || p.key == key;
    if (declared) continue;
    std::string valid;
    for (const auto& p : mode.parameters) valid += (valid.empty() ? "" : ", ") + std::string(p.key);
    throw std::invalid_argument(prefix + key + ": unknown parameter; valid parameters of " +
                                std::string(mode.name) + ": " + (valid.empty() ? "none" : valid));
  }
  std::vector<double> values;
  for (const auto& p : mode.parameters) {
    const double v = settings.find(mode.name, p.key).value_or(p.default_value);
    if (!p.choices.empty() || p.boolean) {
      const double count = p.boolean ? 2.0 : double(p.choices.size());
      if (!(v >= 0.0 && v < count && v == std::floor(v)))
        throw std::invalid_argument(prefix + std::string(p.key) + ": not a valid " +
                                    (p.boolean ? "boolean" : "choice index") + " (got " +
                                    parameter_text(v) + ")");
      values.push_back(v);
      continue;
    }
    if (!std::isfinite(v) || !p.range.contains(v))
      throw std::invalid_argument(prefix + std::string(p.key) + ": " + p.range.describe() +
                                  " (got " + parameter_text(v) + ")");
    values.push_back(v);
  }
  ModeParameters parameters(mode, std::move(values));
  if (mode.check)
    if (const auto problem = mode.check(parameters))
      throw std::invalid_argument(prefix + problem->key + ": " + problem->problem);
  return parameters;
}

std::unique_ptr<HeatTransferMode> make_heat_transfer_mode(std::string_view name,
                                                          const ModeSettings& settings) {
  const ModeDescription* mode = find_heat_transfer_mode(name);
  if (mode == nullptr)
    throw std::invalid_argument("unknown heat-transfer mode \"" + std::string(name) +
                                "\"; valid types are: " + valid_names(registry().modes));
  auto built = mode->make(resolve_mode_parameters(*mode, settings));
  ++registry().constructions[std::string(name)];
  return built;
}

int heat_transfer_mode_constructions(std::string_view name) {
  const auto& counts = registry().constructions;
  const auto it = counts.find(name);
  return it == counts.end() ? 0 : it->second;
}

}  // namespace tmdem::thermal
