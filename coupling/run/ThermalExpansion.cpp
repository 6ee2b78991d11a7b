#include "coupling/run/ThermalExpansion.h"

#include <stdexcept>

namespace tmdem::coupling {

ThermalExpansion::ThermalExpansion(const Scene& scene) {
  for (const auto& p : scene.particles) {
    const double alpha = scene.materials[static_cast<std::size_t>(p.material)].thermal_expansion_per_K;
    radius0_m_.push_back(p.radius_m);
    temperature0_K_.push_back(p.temperature_K);
    alpha_per_K_.push_back(alpha);
    any_ = any_ || alpha != 0.0;
  }
}

void ThermalExpansion::radii(std::span<const double> temperature_K, std::vector<double>& radius_m) const {
  if (temperature_K.size() != radius0_m_.size())
    throw std::logic_error("ThermalExpansion: one temperature per particle expected");
  radius_m.resize(radius0_m_.size());
  for (std::size_t i = 0; i < radius0_m_.size(); ++i)
    radius_m[i] = radius0_m_[i] * (1.0 + alpha_per_K_[i] * (temperature_K[i] - temperature0_K_[i]));
}

}  // namespace tmdem::coupling
