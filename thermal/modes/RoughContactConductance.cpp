#include "thermal/modes/RoughContactConductance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace tmdem::thermal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Exponent of the Cooper-Mikic-Yovanovich plastic correlation h ~ (P / H_mic)^n (Yovanovich 1982).
constexpr double kCmyExponent = 0.95;

double harmonic_mean(double k1, double k2) { return k1 + k2 > 0.0 ? 2.0 * k1 * k2 / (k1 + k2) : 0.0; }

// The softer surface's microhardness, of those given (0: none given).
double softer_microhardness_Pa(const ContactBody& b1, const ContactBody& b2) {
  if (b1.microhardness_Pa > 0.0 && b2.microhardness_Pa > 0.0)
    return std::min(b1.microhardness_Pa, b2.microhardness_Pa);
  return std::max(b1.microhardness_Pa, b2.microhardness_Pa);
}

}  // namespace

double RoughContactResistances::conductance_W_per_K() const {
  // Inside the spot the micro-contacts and the micro-gap conduct side by side.
  const double spot_W_per_K =
      (microcontacts_K_per_W > 0.0 ? 1.0 / microcontacts_K_per_W : kInfinity) +
      (std::isinf(microgap_K_per_W) ? 0.0 : 1.0 / microgap_K_per_W);
  const double spot_K_per_W = std::isinf(spot_W_per_K) ? 0.0 : 1.0 / spot_W_per_K;
  return 1.0 / (macrocontact_K_per_W + spot_K_per_W);
}

double inverse_erfc(double y) {
  if (!(y > 0.0 && y < 2.0)) throw std::invalid_argument("inverse_erfc: y must be in (0, 2)");
  if (y > 1.0) return -inverse_erfc(2.0 - y);  // erfc(-x) = 2 - erfc(x); 2 - y is exact here
  // x >= 0: Newton on ln erfc(x) = ln y, nearly quadratic in x (erfc falls like exp(-x^2), which
  // makes Newton on erfc itself crawl in the tail), kept inside the bracket [lo, hi].
  const double target = std::log(y);
  double lo = 0.0, hi = 27.0;  // erfc(27) < 1e-318
  double x = std::sqrt(-target);
  for (int i = 0; i < 100; ++i) {
    const double e = std::erfc(x);
    const double f = std::log(e) - target;
    if (f == 0.0) return x;
    (f > 0.0 ? lo : hi) = x;  // erfc(x) > y: the root lies above x
    const double slope = -2.0 / std::sqrt(std::numbers::pi) * std::exp(-x * x) / e;
    double next = x - f / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, x))
      return next;
    x = next;
  }
  return x;
}

double hertz_peak_pressure_Pa(const ContactBody& b1, const ContactBody& b2, double normal_force_N) {
  const double a = hertz_contact_radius_m(b1, b2, normal_force_N);
  if (!(a > 0.0)) return 0.0;
  return 3.0 * normal_force_N / (2.0 * std::numbers::pi * a * a);
}

RoughContactResistances rough_contact_resistances(const ContactBody& b1, const ContactBody& b2,
                                                  double normal_force_N, const ContactGas& gas) {
  const double pi = std::numbers::pi;
  const double k = harmonic_mean(b1.conductivity_W_per_mK, b2.conductivity_W_per_mK);
  const double a = hertz_contact_radius_m(b1, b2, normal_force_N);
  RoughContactResistances r;
  r.macrocontact_K_per_W = 1.0 / (2.0 * k * a);
  r.microgap_K_per_W = kInfinity;
  const double sigma = std::hypot(b1.roughness_m, b2.roughness_m);
  if (!(sigma > 0.0)) return r;  // smooth: the spot conducts as a whole (Hertz)
  const double slope = std::hypot(b1.asperity_slope, b2.asperity_slope);
  const double H_mic = softer_microhardness_Pa(b1, b2);
  if (!(slope > 0.0) || !(H_mic > 0.0))
    throw std::invalid_argument(
        "rough contact: surfaces with roughness need an asperity slope > 0 and a microhardness");
  const double P0 = 3.0 * normal_force_N / (2.0 * pi * a * a);
  const double area = pi * a * a;
  r.microcontacts_K_per_W = (1.0 + 0.5 * kCmyExponent) / (1.25 * k * area) * (sigma / slope) *
                            std::pow(H_mic / P0, kCmyExponent);
  // The micro-gap: the mean planes of the rough surfaces lie Y = sqrt(2) sigma a1 apart, which
  // needs 2 P0 / H_mic < 1 (a1 > 0); pressed harder the spot is almost all solid and its gas is
  // not counted.
  const double x = 2.0 * P0 / H_mic;
  if (gas.conductivity_W_per_mK > 0.0 && x < 1.0) {
    const double a1 = inverse_erfc(x);
    const double a2 = inverse_erfc(0.015 * x) - a1;  // 0.03 P0 / H_mic
    const double width_m = 2.0 * std::numbers::sqrt2 * sigma;
    r.microgap_K_per_W = width_m * a2 / (gas.conductivity_W_per_mK * area *
                                         std::log1p(a2 / (a1 + gas.gas_parameter_m / width_m)));
  }
  return r;
}

double rough_contact_conductance_W_per_K(const ContactBody& b1, const ContactBody& b2,
                                         double normal_force_N, const ContactGas& gas) {
  if (!(normal_force_N > 0.0)) return 0.0;
  return rough_contact_resistances(b1, b2, normal_force_N, gas).conductance_W_per_K();
}

}  // namespace tmdem::thermal
