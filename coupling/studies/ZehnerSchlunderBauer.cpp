#include "coupling/studies/ZehnerSchlunderBauer.h"

#include <cmath>
#include <stdexcept>

namespace tmdem::coupling {

ZehnerSchlunderBauerResult zehner_schlunder_bauer(const ZehnerSchlunderBauerInput& in) {
  const double psi = in.porosity;
  if (!(psi > 0.0 && psi < 1.0))
    throw std::invalid_argument("zehner_schlunder_bauer: porosity must lie in (0, 1)");
  if (!(in.k_solid_W_per_mK > 0.0) || !(in.k_fluid_W_per_mK > 0.0) || !(in.diameter_m > 0.0) ||
      !(in.shape_factor > 0.0) || !(in.jump_length_m >= 0.0) || !(in.flattening >= 0.0 && in.flattening <= 1.0) ||
      !(in.emissivity >= 0.0 && in.emissivity <= 1.0) || !(in.temperature_K >= 0.0))
    throw std::invalid_argument("zehner_schlunder_bauer: an input is out of range");
  constexpr double sigma = 5.670374419e-8;  // W/(m^2 K^4)
  ZehnerSchlunderBauerResult out;
  const double kp = in.k_solid_W_per_mK / in.k_fluid_W_per_mK;
  const double kG = 1.0 / (1.0 + in.jump_length_m / in.diameter_m);
  const double krad = in.emissivity > 0.0 ? 4.0 * sigma / (2.0 / in.emissivity - 1.0) *
                                                std::pow(in.temperature_K, 3) * in.diameter_m /
                                                in.k_fluid_W_per_mK
                                          : 0.0;
  const double B = in.shape_factor * std::pow((1.0 - psi) / psi, 10.0 / 9.0);
  const double N = (1.0 + (krad - B * kG) / kp) / kG - B * (1.0 / kG - 1.0) * (1.0 + krad / kp);
  const double log_term =
      std::log((kp + krad) / (B * (kG + (1.0 - kG) * (kp + krad))));
  const double kc = 2.0 / N *
                    (B * (kp + krad - 1.0) / (N * N * kG * kp) * log_term +
                     (B + 1.0) / (2.0 * B) * (krad / kG - B * (1.0 + (1.0 - kG) / kG * krad)) -
                     (B - 1.0) / (N * kG));
  const double root = std::sqrt(1.0 - psi);
  const double ratio = (1.0 - root) * psi * (1.0 / (psi - 1.0 + 1.0 / kG) + krad) +
                       root * (in.flattening * kp + (1.0 - in.flattening) * kc);
  out.k_eff_W_per_mK = ratio * in.k_fluid_W_per_mK;
  out.k_G = kG;
  out.k_rad = krad;
  out.k_c = kc;
  return out;
}

}  // namespace tmdem::coupling
