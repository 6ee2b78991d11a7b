#pragma once
// Thermal expansion of the particles (effects.mechanics = "coupled"): each particle's radius is
// r0 (1 + alpha (T - T0)), r0 and T0 its radius and temperature at the start of the run, alpha
// its material's thermal_expansion (1/K). Masses and moments of inertia are kept (the mass is
// conserved; the inertia's change, of order alpha dT, is left out); walls do not expand.
#include <span>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

class ThermalExpansion {
 public:
  explicit ThermalExpansion(const Scene& scene);
  // Whether some particle's material expands (alpha != 0).
  bool any() const { return any_; }
  // radius_m[i] = r0_i (1 + alpha_i (T_i - T0_i)), m; temperature_K one per particle.
  void radii(std::span<const double> temperature_K, std::vector<double>& radius_m) const;

 private:
  std::vector<double> radius0_m_, temperature0_K_, alpha_per_K_;
  bool any_ = false;
};

}  // namespace tmdem::coupling
