#include "mechanics/contact/NormalLaw.h"

#include <stdexcept>

namespace tmdem::mechanics {

const std::vector<std::string>& normal_law_names() {
  static const std::vector<std::string> names{"rigid", "hertz"};
  return names;
}

const std::string& normal_law_name(NormalLaw law) {
  return normal_law_names()[static_cast<std::size_t>(law)];
}

NormalLaw parse_normal_law(std::string_view name) {
  const auto& names = normal_law_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<NormalLaw>(k);
  std::string valid;
  for (const auto& n : names) valid += (valid.empty() ? "\"" : ", \"") + n + "\"";
  throw std::invalid_argument("mechanics: unknown normal_law \"" + std::string(name) + "\" (valid: " + valid + ")");
}

}  // namespace tmdem::mechanics
